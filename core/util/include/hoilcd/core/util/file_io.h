// Generic file I/O: reads of regular files only (a FIFO or device is refused, never waited on),
// bounded when asked; atomic writes (a reader never sees a half-written file) with an fsync per
// file or batched, content checksums, and PNG encoding with the one atomic PNG writer.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

namespace hoilcd {

// "xxh3-128:<32 lowercase hex digits>" (XXH3 128-bit, canonical big-endian byte order).
std::string ChecksumOf(std::string_view bytes);

// A regular file open for reading: the one check every reader goes through. Opening never
// blocks; a FIFO, device, socket or folder is an InputError(path, "is a FIFO: expected a regular
// file"), a missing or unreadable file InputError(path, "cannot read file ...").
class RegularFile {
 public:
  explicit RegularFile(const std::string& path);
  ~RegularFile();
  RegularFile(const RegularFile&) = delete;
  RegularFile& operator=(const RegularFile&) = delete;

  const std::string& path() const { return path_; }
  // Bytes, as fstat gave them when opened: a header can be checked against it before the body
  // is read. 0 for files whose size stat does not know (/proc), so a bounded reader still reads
  // at most its bound.
  uint64_t size() const { return size_; }
  // The next bytes, up to `max_bytes` (fewer only at the end of the file); InputError(path, ...)
  // on a read error or when they do not fit in memory.
  std::string Read(size_t max_bytes);
  // The same into `into`, without allocating: 0 at the end of the file.
  size_t ReadInto(char* into, size_t max_bytes);

 private:
  std::string path_;
  int fd_ = -1;
  uint64_t size_ = 0;
  uint64_t read_ = 0;  // bytes read so far
};

// ChecksumOf(ReadFileBytes(path)), read block by block (the file is never held whole); InputError
// as ReadFileBytes.
std::string ChecksumOfFile(const std::string& path);

// Whole file as bytes, refused as RegularFile refuses, or when longer than max_bytes
// (InputError(path, "is N bytes: expected at most M")) or than memory holds.
std::string ReadFileBytes(const std::string& path, uint64_t max_bytes = std::numeric_limits<uint64_t>::max());

// Writes to "<path>.tmp.<pid>" in the same directory, fsyncs, renames over path: readers never
// see a half-written file. Creates parent directories. InputError(path, ...) on failure.
void WriteFileAtomic(const std::string& path, std::string_view bytes);

// The same without the fsync: readers still never see a half-written file, and a killed process
// loses nothing, but after a power loss the file may be empty or missing until SyncFiles has
// flushed it. For many files whose listing (a manifest) is written after one SyncFiles of them.
void WriteFileAtomicUnsynced(const std::string& path, std::string_view bytes);

// The names of dir's entries, sorted, a folder's with a trailing '/', without hoilcd's lock file
// (folder_lock.h): what an output folder's guard looks at. A folder that cannot be listed is an
// InputError(dir, "cannot list the folder (...)"), never an empty folder.
std::vector<std::string> ListFolder(const std::string& dir);

// fsyncs every file, then each distinct folder holding one (so their renames are durable).
// InputError(path, ...) on failure.
void SyncFiles(const std::vector<std::string>& paths);

// PNG bytes of a 1-channel CV_8U or CV_16U image (EncodeGreyPng, core/util/png.h) or a BGR CV_8UC3
// one (figures, through OpenCV); the same image always gives the same bytes.
std::string EncodePng(const cv::Mat& image);

// EncodePng(image) written with WriteFileAtomic: the one atomic PNG writer (frames, figures).
void WritePng(const std::string& path, const cv::Mat& image);

}  // namespace hoilcd
