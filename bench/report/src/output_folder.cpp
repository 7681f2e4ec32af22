#include "hoilcd/bench/report/output_folder.h"

#include <algorithm>
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "hoilcd/core/dataset/dataset_folder.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "hoilcd/core/util/json_reader.h"

namespace hoilcd {

namespace fs = std::filesystem;

bool IsEarlierOutput(const std::string& dir, const OutputMarker& marker) {
  std::error_code ec;
  const std::string path = dir + "/" + marker.file;
  if (!fs::is_regular_file(path, ec)) return false;
  const nlohmann::json json = ParseJsonOrDiscarded(ReadFileBytes(path));
  return json.is_object() && std::all_of(marker.keys.begin(), marker.keys.end(),
                                         [&](const std::string& key) { return json.contains(key); });
}

void CheckOutputFolder(const std::string& dir, const OutputMarker& marker) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) return;
  if (!fs::is_directory(dir, ec)) {
    throw InputError(dir,
                     "is a file: expected a folder (new, empty, or holding an earlier hoilcd " + marker.what + ")");
  }
  // Listed first: a folder that cannot be listed is refused by name, never taken as empty.
  const std::vector<std::string> entries = ListFolder(dir);
  if (entries.empty() || IsEarlierOutput(dir, marker)) return;
  throw InputError(dir, "exists, is not empty (it holds " + JoinFileList(entries) + ") and holds no earlier hoilcd " +
                            marker.what + " (" + marker.file +
                            "); refusing to overwrite files in it: choose a new or empty folder");
}

void CreateOutputFolder(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir, "cannot create the folder (" + ec.message() + ")");
}

}  // namespace hoilcd
