// Where hoilcd's shipped data (scenes/, assets/, the scene schema) lives, found at run time so
// that an installed prefix can be moved: $HOILCD_DATA_DIR when set, else the nearest
// share/hoilcd above the binary that holds this code (PREFIX/bin/hoilcd -> PREFIX/share/hoilcd;
// the build tree has build/share/hoilcd linking to the sources; the Python module finds it too).
#pragma once

#include <string>

namespace hoilcd {

// The environment variable that overrides the search.
inline constexpr const char* kDataDirVariable = "HOILCD_DATA_DIR";

// Absolute data folder. InputError when HOILCD_DATA_DIR names no folder, or when it is unset and
// no share/hoilcd (holding scenes/scene.schema.json) is found above the binary.
std::string DataDir();

// The executable or shared object (e.g. the Python module) that this code was loaded from.
std::string BinaryPath();

// The program's path from the target of /proc/self/exe, which Linux suffixes " (deleted)" once
// the file has been replaced or removed while the program runs.
std::string ProgramPathFromLink(const std::string& link_target);

}  // namespace hoilcd
