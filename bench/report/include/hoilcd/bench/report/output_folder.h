// The one guard of every command that writes a folder of results (bench, run, evaluate, inspect):
// a folder that is new, empty or holds an earlier output of the command is written into; any
// other folder is the user's, and is refused before any work, naming what it holds.
#pragma once

#include <string>
#include <vector>

namespace hoilcd {

// How an earlier output is recognised: its marker file, a JSON object with these top-level keys.
struct OutputMarker {
  std::string file;               // e.g. "report.json"
  std::vector<std::string> keys;  // keys the marker's object has, e.g. {"hoilcd_version", "methods"}
  std::string what;               // its name in messages, e.g. "report"
};

// Whether dir holds `marker`'s file as a JSON object with its keys.
bool IsEarlierOutput(const std::string& dir, const OutputMarker& marker);

// InputError(dir, ...) when dir is a file, or a folder that is not empty and holds no marker
// file recognised by `marker` (the message names the folder's entries). A missing dir is fine.
void CheckOutputFolder(const std::string& dir, const OutputMarker& marker);

// Creates dir and its parents; InputError(dir, ...) when it cannot.
void CreateOutputFolder(const std::string& dir);

}  // namespace hoilcd
