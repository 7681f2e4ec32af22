// Which files in a dataset folder are hoilcd's own: the exact names it writes (manifest, side
// files, frames) and the temp files NAME.tmp.PID its atomic writes leave when killed. Clean-up
// deletes only those; anything else in the folder is the user's and is only ever named.
#pragma once

#include <string>
#include <vector>

namespace hoilcd {

// manifest.json, a side file (scene.json, poses.csv, ...), or a frame file
// thermal/NNNNNN.png, radiometric/NNNNNN.png, exr/NNNNNN.exr (a relative path).
bool IsDatasetFileName(const std::string& relative_path);

// "<dataset file name>.tmp.<digits>", the temp name WriteFileAtomic used for it.
bool IsDatasetTempFileName(const std::string& relative_path);

// Relative paths (sorted) of entries under dir that hoilcd did not write: neither dataset
// files nor their temp files (nor the folder's lock file, folder_lock.h, which no listing here
// includes). Folders count only through what they hold. Missing dir: none; a folder that cannot
// be listed: InputError(dir, "cannot list the folder ...").
std::vector<std::string> ForeignFiles(const std::string& dir);

// Relative paths (sorted) of entries under dir other than temp files: what a folder without
// manifest.json holds that a render did not write (a render writes its manifest before any other
// file, so even a file with a dataset file's name, such as scene.json, is the user's there).
std::vector<std::string> NonTempFiles(const std::string& dir);

// Deletes the temp files of a killed run (IsDatasetTempFileName) under dir, nothing else: not
// those of another process that still runs (ProcessAlive). Called under the folder's lock.
void RemoveDatasetTempFiles(const std::string& dir);

// Deletes hoilcd's own files under dir (dataset files and their temp files) and the frame
// folders they leave empty; leaves everything else. Returns ForeignFiles(dir) afterwards.
std::vector<std::string> RemoveDatasetFiles(const std::string& dir);

// "a, b, c and 4 more": a short list of paths for an error message.
std::string JoinFileList(const std::vector<std::string>& paths, size_t max_listed = 3);

}  // namespace hoilcd
