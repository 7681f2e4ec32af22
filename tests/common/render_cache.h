// Rendered fixtures cached on disk within one ctest run. A render is keyed by what decides its
// bytes (the caller's key text: the scene file's bytes and overrides) and by the binary that
// renders it (this test executable: a rebuild gives another key). It is made once into the run's
// cache folder, HOILCD_TEST_RENDER_CACHE (emptied by the test render_cache_reset at the start of
// every ctest run), and each test gets hard links to its files in a folder of its own. Without the
// variable (a test binary run by hand) every call renders. docs/guide/testing.md describes it.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include <unistd.h>

#include "hoilcd/core/util/file_io.h"

namespace hoilcd::test {

// The checksum of this process's executable: the render code that a cached folder came from.
inline const std::string& ThisBinaryChecksum() {
  static const std::string checksum = ChecksumOfFile("/proc/self/exe");
  return checksum;
}

// Each file under `dir` with its size, modification time and mode, sorted: what a write into a
// file in place (or a chmod) changes, so a hard-linked cache entry can be checked before each use.
inline std::string FileStates(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::vector<std::string> lines;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    lines.push_back(fs::relative(e.path(), dir).string() + " " + std::to_string(e.file_size()) + " " +
                    std::to_string(e.last_write_time().time_since_epoch().count()) + " " +
                    std::to_string(static_cast<unsigned>(e.status().permissions())));
  }
  std::sort(lines.begin(), lines.end());
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

// Makes `dir` hold what `render(dir)` writes there. With the cache on and `dir` missing or empty,
// `render` runs at most once per key and binary in a ctest run: into a folder of this process,
// renamed into the cache (rename is atomic; when another test got there first, its entry is kept
// and ours removed), then hard-linked into `dir` (copied across file systems). A test may delete,
// add or replace files in its folder (hoilcd writes through a rename), never write into one in
// place: that would change the cache, and the next use of the entry fails, saying so.
inline void CachedRender(const std::string& key_text, const std::string& dir,
                         const std::function<void(const std::string&)>& render) {
  namespace fs = std::filesystem;
  const char* cache = std::getenv("HOILCD_TEST_RENDER_CACHE");
  std::error_code ec;
  if (cache == nullptr || *cache == '\0' || (fs::exists(dir, ec) && !fs::is_empty(dir, ec))) {
    render(dir);
    return;
  }
  const std::string checksum = ChecksumOf(key_text + "\nrendered by " + ThisBinaryChecksum());
  const fs::path entry = fs::path(cache) / checksum.substr(checksum.find(':') + 1);  // holds render/ and files.txt
  if (!fs::is_directory(entry, ec)) {
    static std::atomic<int> made{0};
    const fs::path mine = entry.string() + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(made++);
    try {
      fs::create_directories(mine);
      render((mine / "render").string());
      WriteFileAtomic((mine / "files.txt").string(), FileStates(mine / "render"));
    } catch (...) {
      fs::remove_all(mine, ec);
      throw;
    }
    fs::rename(mine, entry, ec);  // fails (ENOTEMPTY) when another test's rename came first
    if (ec) fs::remove_all(mine);
  }
  if (FileStates(entry / "render") != ReadFileBytes((entry / "files.txt").string())) {
    throw std::runtime_error("the cached render " + entry.string() + " was changed since it was made: a test wrote " +
                             "into a hard-linked fixture file in place (tests/common/render_cache.h)");
  }
  fs::create_directories(dir);
  fs::copy(entry / "render", dir, fs::copy_options::recursive | fs::copy_options::create_hard_links, ec);
  if (ec) {  // another file system: copies
    fs::remove_all(dir);
    fs::create_directories(dir);
    fs::copy(entry / "render", dir, fs::copy_options::recursive);
  }
}

}  // namespace hoilcd::test
