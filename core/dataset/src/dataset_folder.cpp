#include "hoilcd/core/dataset/dataset_folder.h"

#include <algorithm>
#include <filesystem>
#include <utility>

#include <unistd.h>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/folder_lock.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

constexpr const char* kSideFiles[] = {"manifest.json", "scene.json",      "poses.csv", "poses_tum.txt", "persons.json",
                                      "events.json",   "footprints.json", "runs.json", "thermal.mp4",   "ros2.mcap"};
constexpr const char* kFrameFolders[] = {"thermal", "radiometric", "exr"};

bool AllDigits(const std::string& text, size_t min_length) {
  return text.size() >= min_length &&
         std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// Every entry under dir that is not a folder, as relative paths; symlinks are not followed. The
// folder's lock file (folder_lock.h) is hoilcd's bookkeeping, not a file of the dataset: left out.
std::vector<std::string> FilesUnder(const std::string& dir) {
  std::vector<std::string> files;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return files;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->is_directory(ec) && !it->is_symlink(ec)) continue;
    std::string relative = fs::relative(it->path(), dir, ec).generic_string();
    if (relative != kFolderLockFile) files.push_back(std::move(relative));
  }
  if (ec) throw InputError(dir, "cannot list the folder (" + ec.message() + ")");
  std::sort(files.begin(), files.end());
  return files;
}

// "NAME.tmp.PID" of a process that runs and is not this one: still being written (by a process
// that took no folder lock, such as an older hoilcd), so not to be removed. This process's own are
// left over: it removes them before it writes any.
bool TempFileOfAnotherLiveProcess(const std::string& temp_name) {
  const std::string digits = temp_name.substr(temp_name.rfind(".tmp.") + 5);
  if (digits.size() > 9) return false;  // no pid is that long
  const long pid = std::stol(digits);
  return pid != static_cast<long>(::getpid()) && ProcessAlive(pid);
}

void Remove(const fs::path& path) {
  std::error_code ec;
  fs::remove(path, ec);
  if (ec) throw InputError(path.string(), "cannot delete (" + ec.message() + ")");
}

}  // namespace

bool IsDatasetFileName(const std::string& relative_path) {
  for (const char* side : kSideFiles) {
    if (relative_path == side) return true;
  }
  const size_t slash = relative_path.find('/');
  if (slash == std::string::npos) return false;
  const std::string folder = relative_path.substr(0, slash);
  const std::string name = relative_path.substr(slash + 1);
  const std::string extension = folder == "exr" ? ".exr" : ".png";
  if (std::none_of(std::begin(kFrameFolders), std::end(kFrameFolders), [&](const char* f) { return folder == f; }) ||
      name.size() <= extension.size() ||
      name.compare(name.size() - extension.size(), extension.size(), extension) != 0) {
    return false;
  }
  return AllDigits(name.substr(0, name.size() - extension.size()), 6);
}

bool IsDatasetTempFileName(const std::string& relative_path) {
  const size_t at = relative_path.rfind(".tmp.");
  return at != std::string::npos && AllDigits(relative_path.substr(at + 5), 1) &&
         IsDatasetFileName(relative_path.substr(0, at));
}

std::vector<std::string> ForeignFiles(const std::string& dir) {
  std::vector<std::string> foreign;
  for (const std::string& file : FilesUnder(dir)) {
    if (!IsDatasetFileName(file) && !IsDatasetTempFileName(file)) foreign.push_back(file);
  }
  return foreign;
}

std::vector<std::string> NonTempFiles(const std::string& dir) {
  std::vector<std::string> files;
  for (const std::string& file : FilesUnder(dir)) {
    if (!IsDatasetTempFileName(file)) files.push_back(file);
  }
  return files;
}

void RemoveDatasetTempFiles(const std::string& dir) {
  for (const std::string& file : FilesUnder(dir)) {
    if (IsDatasetTempFileName(file) && !TempFileOfAnotherLiveProcess(file)) Remove(fs::path(dir) / file);
  }
}

std::vector<std::string> RemoveDatasetFiles(const std::string& dir) {
  for (const std::string& file : FilesUnder(dir)) {
    if (IsDatasetFileName(file) || IsDatasetTempFileName(file)) Remove(fs::path(dir) / file);
  }
  for (const char* folder : kFrameFolders) {
    std::error_code ec;
    if (fs::is_empty(fs::path(dir) / folder, ec)) fs::remove(fs::path(dir) / folder, ec);
  }
  return ForeignFiles(dir);
}

std::string JoinFileList(const std::vector<std::string>& paths, size_t max_listed) {
  std::string text;
  const size_t listed = std::min(paths.size(), max_listed);
  for (size_t i = 0; i < listed; ++i) {
    if (i > 0) text += i + 1 == paths.size() ? " and " : ", ";
    text += paths[i];
  }
  if (paths.size() > listed) text += " and " + std::to_string(paths.size() - listed) + " more";
  return text;
}

}  // namespace hoilcd
