// Helpers shared by the fuzz targets: a per-process scratch folder for parsers that read files.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "hoilcd/core/dataset.h"

namespace hoilcd::fuzz {

// Writes the input to SCRATCH/name (SCRATCH: one folder per fuzzing process) and returns the path.
inline std::string WriteScratchFile(const std::string& name, const uint8_t* data, size_t size) {
  static const std::filesystem::path scratch = [] {
    const auto dir = std::filesystem::temp_directory_path() / ("hoilcd_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir;
  }();
  const std::string path = (scratch / name).string();
  WriteFileAtomic(path, std::string_view(reinterpret_cast<const char*>(data), size));
  return path;
}

}  // namespace hoilcd::fuzz
