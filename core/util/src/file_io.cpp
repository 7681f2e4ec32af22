#include "hoilcd/core/util/file_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <xxhash.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <memory>
#include <set>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/png.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

constexpr const char* kChecksumPrefix = "xxh3-128:";

// The checksum text of a finished XXH3-128 hash.
std::string ChecksumText(XXH128_hash_t hash) {
  XXH128_canonical_t canonical;
  XXH128_canonicalFromHash(&canonical, hash);
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out = kChecksumPrefix;
  for (unsigned char byte : canonical.digest) {
    out += kHex[byte >> 4];
    out += kHex[byte & 15];
  }
  return out;
}

int OpenForReading(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw InputError(path, "cannot read file (missing or not readable)");
  return fd;
}

// Up to `size` bytes of fd into `into` (0 at the end of the file), retried on EINTR; on an error
// closes fd and throws InputError(path, ...).
size_t ReadSome(int fd, char* into, size_t size, const std::string& path) {
  for (;;) {
    const ssize_t got = ::read(fd, into, size);
    if (got >= 0) return static_cast<size_t>(got);
    if (errno == EINTR) continue;
    const int error = errno;
    ::close(fd);
    // A folder opens but does not read (EISDIR): still "not readable" to the caller.
    throw InputError(path, error == EISDIR ? "cannot read file (missing or not readable)"
                                           : std::string("cannot read file (") + std::strerror(error) + ")");
  }
}

}  // namespace

std::string ChecksumOf(std::string_view bytes) { return ChecksumText(XXH3_128bits(bytes.data(), bytes.size())); }

std::string ChecksumOfFile(const std::string& path) {
  const std::unique_ptr<XXH3_state_t, XXH_errorcode (*)(XXH3_state_t*)> state(XXH3_createState(), XXH3_freeState);
  HOILCD_CHECK(state != nullptr && XXH3_128bits_reset(state.get()) == XXH_OK);
  // Block by block into one uninitialised buffer: a dataset's files (~1 GB) are never held whole,
  // zeroed or faulted in anew.
  constexpr size_t kBlock = size_t{1} << 18;
  const std::unique_ptr<char[]> block(new char[kBlock]);
  const int fd = OpenForReading(path);  // opened last: nothing below throws but ReadSome, which closes it
  while (const size_t got = ReadSome(fd, block.get(), kBlock, path)) {
    XXH3_128bits_update(state.get(), block.get(), got);
  }
  ::close(fd);
  return ChecksumText(XXH3_128bits_digest(state.get()));
}

std::string ReadFileBytes(const std::string& path) {
  const int fd = OpenForReading(path);
  struct stat st {};
  // Sized by fstat, read in large blocks; the loop also reads files whose size stat does not
  // know (/proc) or that grow while read.
  std::string bytes(::fstat(fd, &st) == 0 && st.st_size > 0 ? static_cast<size_t>(st.st_size) + 1
                                                             : size_t{1} << 16,
                    '\0');
  size_t size = 0;
  for (;;) {
    if (size == bytes.size()) bytes.resize(bytes.size() * 2);
    const size_t got = ReadSome(fd, bytes.data() + size, bytes.size() - size, path);
    if (got == 0) break;
    size += got;
  }
  ::close(fd);
  bytes.resize(size);
  return bytes;
}

namespace {

void WriteAtomic(const std::string& path, std::string_view bytes, bool sync) {
  const fs::path target(path);
  if (target.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(target.parent_path(), ec);
    if (ec) throw InputError(path, "cannot create directory: " + ec.message());
  }
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw InputError(path, std::string("cannot write file: ") + std::strerror(errno));
  auto fail = [&](const char* what) {
    const int err = errno;
    ::close(fd);
    ::unlink(tmp.c_str());
    throw InputError(path, std::string(what) + std::strerror(err));
  };
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("cannot write file: ");
    }
    done += static_cast<size_t>(n);
  }
  if (sync && ::fsync(fd) != 0) fail("cannot flush file to disk: ");
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw InputError(path, std::string("cannot write file: ") + std::strerror(err));
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw InputError(path, std::string("cannot rename temporary file into place: ") +
                               std::strerror(err));
  }
}

// fsync of an existing file or folder (opened read-only: enough for fsync on Linux).
void Sync(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw InputError(path, std::string("cannot open to flush it to disk: ") + std::strerror(errno));
  const int result = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (result != 0) throw InputError(path, std::string("cannot flush file to disk: ") + std::strerror(err));
}

}  // namespace

void WriteFileAtomic(const std::string& path, std::string_view bytes) { WriteAtomic(path, bytes, true); }

void WriteFileAtomicUnsynced(const std::string& path, std::string_view bytes) { WriteAtomic(path, bytes, false); }

void SyncFiles(const std::vector<std::string>& paths) {
  std::set<std::string> folders;
  for (const std::string& path : paths) {
    Sync(path);
    folders.insert(fs::path(path).has_parent_path() ? fs::path(path).parent_path().string() : ".");
  }
  for (const std::string& folder : folders) Sync(folder);  // makes the renames durable
}

std::string EncodePng(const cv::Mat& image) {
  HOILCD_CHECK_MSG((image.channels() == 1 && (image.depth() == CV_8U || image.depth() == CV_16U)) ||
                       image.type() == CV_8UC3,
                   "EncodePng takes a 1-channel CV_8U or CV_16U image or a CV_8UC3 one");
  if (image.channels() == 1) return EncodeGreyPng(image);  // the frames: libdeflate (core/util/png.h)
  std::vector<uchar> buffer;
  HOILCD_CHECK(cv::imencode(".png", image, buffer));  // colour figures: OpenCV's default parameters
  return std::string(buffer.begin(), buffer.end());
}

void WritePng(const std::string& path, const cv::Mat& image) {
  HOILCD_CHECK_MSG(!image.empty(), "WritePng of an empty image to " << path);
  WriteFileAtomic(path, EncodePng(image));
}

}  // namespace hoilcd
