// Helpers shared by the fuzz targets: a per-process scratch folder for parsers that read files.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace hoilcd::fuzz {

// Writes the input to SCRATCH/name (SCRATCH: one folder per fuzzing process) and returns the path.
inline std::string WriteScratchFile(const std::string& name, const uint8_t* data, size_t size) {
  // Removed when the fuzzing process ends normally.
  struct Scratch {
    std::filesystem::path dir = std::filesystem::temp_directory_path() / ("hoilcd_fuzz_" + std::to_string(::getpid()));
    Scratch() { std::filesystem::create_directories(dir); }
    ~Scratch() {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  };
  static const Scratch scratch_dir;
  const std::filesystem::path& scratch = scratch_dir.dir;
  const std::string path = (scratch / name).string();
  // A plain write: WriteFileAtomic's fsync would cost more than the parse under test.
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace hoilcd::fuzz
