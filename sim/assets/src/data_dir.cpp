#include "hoilcd/sim/assets/data_dir.h"

#include <cstdlib>
#include <filesystem>

#include <link.h>

#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

struct Lookup {
  uintptr_t address = 0;
  std::string name;  // the object's path; "" for the main program
  bool found = false;
};

// dladdr names the main program by argv[0] (relative, maybe not a path at all), so the
// loaded object holding `address` is found among the program headers instead.
int FindObject(dl_phdr_info* info, size_t, void* data) {
  Lookup* lookup = static_cast<Lookup*>(data);
  for (int i = 0; i < info->dlpi_phnum; ++i) {
    const ElfW(Phdr)& header = info->dlpi_phdr[i];
    if (header.p_type != PT_LOAD) continue;
    const uintptr_t begin = info->dlpi_addr + header.p_vaddr;
    if (lookup->address >= begin && lookup->address < begin + header.p_memsz) {
      lookup->name = info->dlpi_name != nullptr ? info->dlpi_name : "";
      lookup->found = true;
      return 1;
    }
  }
  return 0;
}

}  // namespace

std::string ProgramPathFromLink(const std::string& link_target) {
  const std::string suffix = " (deleted)";
  if (link_target.size() > suffix.size() &&
      link_target.compare(link_target.size() - suffix.size(), suffix.size(), suffix) == 0) {
    return link_target.substr(0, link_target.size() - suffix.size());
  }
  return link_target;
}

std::string BinaryPath() {
  Lookup lookup;
  lookup.address = reinterpret_cast<uintptr_t>(&BinaryPath);
  dl_iterate_phdr(FindObject, &lookup);
  std::error_code error;
  if (!lookup.found || lookup.name.empty()) {
    // The running program, also once a rebuild or an upgrade has replaced its file (a long suite):
    // its folder, and the share/hoilcd beside it, are still there.
    const fs::path target = fs::read_symlink("/proc/self/exe", error);
    if (!error) return ProgramPathFromLink(target.string());
    return "/proc/self/exe";
  }
  const fs::path resolved = fs::canonical(lookup.name, error);
  return error ? lookup.name : resolved.string();
}

std::string DataDir() {
  std::error_code error;
  if (const char* variable = std::getenv(kDataDirVariable); variable != nullptr && variable[0] != '\0') {
    if (!fs::is_directory(variable, error)) {
      throw InputError(kDataDirVariable, "'" + std::string(variable) +
                                             "' is not a folder; expected the folder holding hoilcd's "
                                             "scenes/ and assets/ (or unset it to use the installed ones)");
    }
    return fs::absolute(variable).lexically_normal().string();
  }
  const fs::path binary = BinaryPath();
  for (fs::path dir = binary.parent_path(); !dir.empty(); dir = dir.parent_path()) {
    const fs::path candidate = dir / "share" / "hoilcd";
    if (fs::is_regular_file(candidate / "scenes" / "scene.schema.json", error)) return candidate.string();
    if (dir == dir.root_path()) break;
  }
  throw InputError(kDataDirVariable,
                   "hoilcd's data folder (share/hoilcd with scenes/ and assets/) was not found "
                   "above " +
                       binary.string() + "; set " + kDataDirVariable + " to it");
}

}  // namespace hoilcd
