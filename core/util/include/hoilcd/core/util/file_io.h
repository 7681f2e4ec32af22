// Generic file I/O: whole-file reads, atomic writes (a reader never sees a half-written file)
// with an fsync per file or batched, content checksums, and PNG encoding with the one atomic
// PNG writer.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace hoilcd {

// "xxh3-128:<32 lowercase hex digits>" (XXH3 128-bit, canonical big-endian byte order).
std::string ChecksumOf(std::string_view bytes);

// ChecksumOf(ReadFileBytes(path)), read block by block (the file is never held whole); InputError
// as ReadFileBytes.
std::string ChecksumOfFile(const std::string& path);

// Whole file as bytes; InputError(path, "cannot read ...") if missing or unreadable.
std::string ReadFileBytes(const std::string& path);

// Writes to "<path>.tmp.<pid>" in the same directory, fsyncs, renames over path: readers never
// see a half-written file. Creates parent directories. InputError(path, ...) on failure.
void WriteFileAtomic(const std::string& path, std::string_view bytes);

// The same without the fsync: readers still never see a half-written file, and a killed process
// loses nothing, but after a power loss the file may be empty or missing until SyncFiles has
// flushed it. For many files whose listing (a manifest) is written after one SyncFiles of them.
void WriteFileAtomicUnsynced(const std::string& path, std::string_view bytes);

// fsyncs every file, then each distinct folder holding one (so their renames are durable).
// InputError(path, ...) on failure.
void SyncFiles(const std::vector<std::string>& paths);

// PNG bytes of a 1-channel CV_8U or CV_16U image (EncodeGreyPng, core/util/png.h) or a BGR CV_8UC3
// one (figures, through OpenCV); the same image always gives the same bytes.
std::string EncodePng(const cv::Mat& image);

// EncodePng(image) written with WriteFileAtomic: the one atomic PNG writer (frames, figures).
void WritePng(const std::string& path, const cv::Mat& image);

}  // namespace hoilcd
