#include "hoilcd/core/util/atomic_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <unistd.h>

#include "hoilcd/core/util/error.h"

namespace hoilcd {

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  const std::filesystem::path target(path_);
  if (target.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(target.parent_path(), ec);
    if (ec) throw InputError(path_, "cannot create directory: " + ec.message());
  }
  temp_path_ = path_ + ".tmp." + std::to_string(::getpid());
  fd_ = ::open(temp_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw InputError(path_, std::string("cannot write file: ") + std::strerror(errno));
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) {
    ::close(fd_);
    ::unlink(temp_path_.c_str());
  }
}

void AtomicFile::Fail(const char* what, int err) {
  ::close(fd_);
  fd_ = -1;
  ::unlink(temp_path_.c_str());
  throw InputError(path_, std::string(what) + std::strerror(err));
}

void AtomicFile::Write(std::string_view bytes) {
  HOILCD_CHECK_MSG(fd_ >= 0, "AtomicFile::Write after Commit or a failure: " << path_);
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      Fail("cannot write file: ", errno);
    }
    done += static_cast<size_t>(n);
  }
  size_ += bytes.size();
}

void AtomicFile::Commit(bool sync) {
  HOILCD_CHECK_MSG(fd_ >= 0, "AtomicFile::Commit twice or after a failure: " << path_);
  if (sync && ::fsync(fd_) != 0) Fail("cannot flush file to disk: ", errno);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(temp_path_.c_str());
    throw InputError(path_, std::string("cannot write file: ") + std::strerror(err));
  }
  if (::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    const int err = errno;
    ::unlink(temp_path_.c_str());
    throw InputError(path_, std::string("cannot rename temporary file into place: ") + std::strerror(err));
  }
}

}  // namespace hoilcd
