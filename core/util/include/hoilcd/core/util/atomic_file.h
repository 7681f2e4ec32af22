// A file written in pieces and put in place atomically: the bytes go to "<path>.tmp.<pid>" in the
// same folder and Commit() renames it over path, so a reader never sees a half-written file. For
// outputs too large to hold in memory (an MCAP bag); WriteFileAtomic (file_io.h) writes through it.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace hoilcd {

class AtomicFile {
 public:
  // Creates path's parent folders and opens the temp file; InputError(path, ...) on failure.
  explicit AtomicFile(std::string path);
  // Without Commit(), the temp file is removed: the target is left as it was.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  // Appends bytes; InputError(path, ...) on a write error.
  void Write(std::string_view bytes);
  uint64_t size() const { return size_; }  // bytes written so far
  // fsyncs (when sync) and renames the temp file over path; once only.
  void Commit(bool sync = true);
  const std::string& path() const { return path_; }

 private:
  [[noreturn]] void Fail(const char* what, int err);  // closes, removes the temp file, throws

  std::string path_;
  std::string temp_path_;
  int fd_ = -1;
  uint64_t size_ = 0;
};

}  // namespace hoilcd
