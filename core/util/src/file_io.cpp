#include "hoilcd/core/util/file_io.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <new>
#include <set>
#include <vector>

#include <fcntl.h>
#include <opencv2/imgcodecs.hpp>
#include <sys/stat.h>
#include <unistd.h>
#include <xxhash.h>

#include "hoilcd/core/util/atomic_file.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/folder_lock.h"
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

// What a file that is not regular is, for the message that refuses it.
std::string KindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "an unknown kind of file";
}

std::string NotRegular(mode_t mode) { return "is " + KindOf(mode) + ": expected a regular file"; }

}  // namespace

std::string ChecksumOf(std::string_view bytes) { return ChecksumText(XXH3_128bits(bytes.data(), bytes.size())); }

RegularFile::RegularFile(const std::string& path) : path_(path) {
  // Refused by stat first, so a device is not even opened; then by fstat of what was opened, in
  // case the path changed in between. O_NONBLOCK: opening a FIFO must not wait for a writer (it
  // changes nothing for a regular file).
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0 && !S_ISREG(info.st_mode)) throw InputError(path, NotRegular(info.st_mode));
  fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) throw InputError(path, "cannot read file (missing or not readable)");
  if (::fstat(fd_, &info) != 0 || !S_ISREG(info.st_mode)) {
    const std::string what = NotRegular(info.st_mode);
    ::close(fd_);
    throw InputError(path, what);
  }
  size_ = static_cast<uint64_t>(info.st_size);
}

RegularFile::~RegularFile() { ::close(fd_); }

size_t RegularFile::ReadInto(char* into, size_t max_bytes) {
  for (;;) {
    const ssize_t got = ::read(fd_, into, max_bytes);
    if (got >= 0) {
      read_ += static_cast<uint64_t>(got);
      return static_cast<size_t>(got);
    }
    if (errno != EINTR) throw InputError(path_, std::string("cannot read file (") + std::strerror(errno) + ")");
  }
}

std::string RegularFile::Read(size_t max_bytes) {
  constexpr size_t kFirstBlock = size_t{1} << 16;
  std::string bytes;
  size_t size = 0;
  try {
    // Sized by what fstat says is left, with one byte more (the read that finds the end), then
    // doubled for files whose size stat does not know (/proc) or that grow while read; never
    // beyond max_bytes.
    const uint64_t left = size_ > read_ ? size_ - read_ : 0;
    bytes.resize(static_cast<size_t>(std::min<uint64_t>(max_bytes, size_ == 0 ? kFirstBlock : left + 1)));
    for (;;) {
      if (size == bytes.size()) {
        if (size == max_bytes) break;
        bytes.resize(max_bytes - size > std::max(size, kFirstBlock) ? size + std::max(size, kFirstBlock) : max_bytes);
      }
      const size_t got = ReadInto(bytes.data() + size, bytes.size() - size);
      if (got == 0) break;
      size += got;
    }
  } catch (const std::bad_alloc&) {
    throw InputError(path_, "is " + std::to_string(size_) + " bytes: more than this machine can hold in memory");
  }
  bytes.resize(size);
  return bytes;
}

std::string ChecksumOfFile(const std::string& path) {
  const std::unique_ptr<XXH3_state_t, XXH_errorcode (*)(XXH3_state_t*)> state(XXH3_createState(), XXH3_freeState);
  HOILCD_CHECK(state != nullptr && XXH3_128bits_reset(state.get()) == XXH_OK);
  // Block by block into one uninitialised buffer: a dataset's files (~1 GB) are never held whole,
  // zeroed or faulted in anew.
  constexpr size_t kBlock = size_t{1} << 18;
  const std::unique_ptr<char[]> block(new char[kBlock]);
  RegularFile file(path);
  while (const size_t got = file.ReadInto(block.get(), kBlock)) {
    XXH3_128bits_update(state.get(), block.get(), got);
  }
  return ChecksumText(XXH3_128bits_digest(state.get()));
}

std::string ReadFileBytes(const std::string& path, uint64_t max_bytes) {
  RegularFile file(path);
  const auto too_long = [&](const std::string& size) {
    return InputError(path, "is " + size + " bytes: expected at most " + std::to_string(max_bytes));
  };
  if (file.size() > max_bytes) throw too_long(std::to_string(file.size()));
  // One byte past the bound tells a file that stat did not size (/proc) and is too long.
  const size_t bound = max_bytes < std::numeric_limits<size_t>::max() ? static_cast<size_t>(max_bytes) + 1
                                                                      : std::numeric_limits<size_t>::max();
  std::string bytes = file.Read(bound);
  if (bytes.size() > max_bytes) throw too_long("more than " + std::to_string(max_bytes));
  return bytes;
}

namespace {

void WriteAtomic(const std::string& path, std::string_view bytes, bool sync) {
  AtomicFile file(path);
  file.Write(bytes);
  file.Commit(sync);
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

std::vector<std::string> ListFolder(const std::string& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name == kFolderLockFile) continue;
    std::error_code kind;
    names.push_back(name + (it->is_directory(kind) ? "/" : ""));
  }
  if (ec) throw InputError(dir, "cannot list the folder (" + ec.message() + ")");
  std::sort(names.begin(), names.end());
  return names;
}

void SyncFiles(const std::vector<std::string>& paths) {
  std::set<std::string> folders;
  for (const std::string& path : paths) {
    Sync(path);
    folders.insert(fs::path(path).has_parent_path() ? fs::path(path).parent_path().string() : ".");
  }
  for (const std::string& folder : folders) Sync(folder);  // makes the renames durable
}

std::string EncodePng(const cv::Mat& image) {
  HOILCD_CHECK_MSG(
      (image.channels() == 1 && (image.depth() == CV_8U || image.depth() == CV_16U)) || image.type() == CV_8UC3,
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
