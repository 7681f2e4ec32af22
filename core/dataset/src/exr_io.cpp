#include "hoilcd/core/dataset/exr_io.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string_view>

#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/error.h"

namespace hoilcd {
namespace {

// OpenEXR writes through an OStream; this one appends to a string so frames can be written
// atomically and checksummed before they touch the disk.
class StringOStream : public Imf::OStream {
 public:
  StringOStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    if (pos_ + n > data_.size()) data_.resize(pos_ + n);
    std::memcpy(&data_[pos_], c, n);
    pos_ += n;
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = pos; }
  std::string& data() { return data_; }

 private:
  std::string data_;
  uint64_t pos_ = 0;
};

}  // namespace

namespace {

Imf::Compression ToImf(ExrCompression c) {
  switch (c) {
    case ExrCompression::kNone:
      return Imf::NO_COMPRESSION;
    case ExrCompression::kRle:
      return Imf::RLE_COMPRESSION;
    case ExrCompression::kZips:
      return Imf::ZIPS_COMPRESSION;
    case ExrCompression::kZip:
      return Imf::ZIP_COMPRESSION;
    case ExrCompression::kPiz:
      return Imf::PIZ_COMPRESSION;
  }
  return Imf::ZIP_COMPRESSION;
}

Imf::PixelType PixelTypeOf(const cv::Mat& mat) {
  if (mat.type() == CV_16F) return Imf::HALF;
  if (mat.type() == CV_32S) return Imf::UINT;
  HOILCD_CHECK_MSG(mat.type() == CV_32F, "EncodeExr takes CV_32F, CV_16F or CV_32S channels");
  return Imf::FLOAT;
}

constexpr int kMaxExrSidePx = 4096;  // far above any thermal camera
constexpr int kMaxExrChannels = 16;  // hoilcd writes 5

// OpenEXR 3.1 allocates an attribute's declared size before reading it: a 439-byte file that
// declares a huge attribute takes seconds and gigabytes (found by fuzz_dataset). Hand-written
// walk of the documented header layout (magic, version, then per header "name\0type\0" int32
// size and value, ending in \0): every attribute must fit in the file, and the data window
// (which sizes OpenEXR's line buffers) must be a frame's size, before OpenEXR reads it.
// OpenEXR reads a known attribute type by its own layout, not by the size the file declares, so
// a size that disagrees with the value puts every later attribute at the wrong offset (and a
// garbage size then allocates gigabytes). True when `value` is exactly what OpenEXR will read.
bool ValueMatchesType(const std::string& type, std::string_view value) {
  static const std::map<std::string, size_t> kFixedSize = {{"box2i", 16},
                                                           {"box2f", 16},
                                                           {"compression", 1},
                                                           {"double", 8},
                                                           {"envmap", 1},
                                                           {"float", 4},
                                                           {"int", 4},
                                                           {"keycode", 28},
                                                           {"lineOrder", 1},
                                                           {"m33f", 36},
                                                           {"m33d", 72},
                                                           {"m44f", 64},
                                                           {"m44d", 128},
                                                           {"rational", 8},
                                                           {"tiledesc", 9},
                                                           {"timecode", 8},
                                                           {"v2i", 8},
                                                           {"v2f", 8},
                                                           {"v2d", 16},
                                                           {"v3i", 12},
                                                           {"v3f", 12},
                                                           {"v3d", 24},
                                                           {"chromaticities", 32},
                                                           {"deepImageState", 1}};
  if (const auto fixed = kFixedSize.find(type); fixed != kFixedSize.end()) return value.size() == fixed->second;
  if (type == "chlist") {  // entries "name\0" + 16 bytes, ended by an empty name
    size_t at = 0;
    while (at < value.size() && value[at] != '\0') {
      const size_t end = value.find('\0', at);
      if (end == std::string_view::npos || end - at > 255 || value.size() - (end + 1) < 16) return false;
      at = end + 1 + 16;
    }
    return at + 1 == value.size();
  }
  if (type == "preview") {  // width, height, then width * height RGBA bytes
    if (value.size() < 8) return false;
    uint64_t width = 0, height = 0;
    for (int i = 3; i >= 0; --i) {
      width = (width << 8) | static_cast<unsigned char>(value[i]);
      height = (height << 8) | static_cast<unsigned char>(value[4 + i]);
    }
    return value.size() - 8 == width * height * 4;  // each factor < 2^32: no overflow in 64 bits
  }
  return true;  // strings, vectors and unknown (opaque) types are read by the declared size
}

// Where the header (all headers of a multi-part file) ends, or 0 if an attribute runs past the
// file's end, disagrees with its type's size, or the data window is not a frame's.
size_t HeaderEnd(const std::string& bytes) {
  if (bytes.size() < 8 || bytes.compare(0, 4, "\x76\x2f\x31\x01") != 0) return 0;
  const bool multipart = (static_cast<unsigned char>(bytes[5]) & 0x10) != 0;
  size_t at = 8;
  bool header_empty = true;
  auto skip_name = [&] {
    const size_t end = bytes.find('\0', at);
    if (end == std::string::npos || end - at > 255) return false;
    at = end + 1;
    return true;
  };
  while (at < bytes.size()) {
    if (bytes[at] == '\0') {  // end of a header; a multi-part list ends with an empty one
      ++at;
      if (!multipart || header_empty) return at;
      header_empty = true;
      continue;
    }
    header_empty = false;
    auto int32_at = [&](size_t where) {
      uint32_t value = 0;
      for (int i = 3; i >= 0; --i) value = (value << 8) | static_cast<unsigned char>(bytes[where + i]);
      return value;
    };
    const size_t name_at = at;
    if (!skip_name()) return 0;
    const size_t type_at = at;
    if (!skip_name() || bytes.size() - at < 4) return 0;
    const std::string type = bytes.substr(type_at, at - 1 - type_at);
    const uint32_t size = int32_at(at);
    at += 4;
    if (size > bytes.size() - at) return 0;
    if (!ValueMatchesType(type, std::string_view(bytes).substr(at, size))) return 0;
    if (bytes.compare(name_at, 11, std::string("dataWindow\0", 11)) == 0 && size == 16) {
      const int64_t width = int64_t{static_cast<int32_t>(int32_at(at + 8))} - static_cast<int32_t>(int32_at(at)) + 1;
      const int64_t height =
          int64_t{static_cast<int32_t>(int32_at(at + 12))} - static_cast<int32_t>(int32_at(at + 4)) + 1;
      if (width < 1 || height < 1 || width > kMaxExrSidePx || height > kMaxExrSidePx) return 0;
    }
    at += size;
  }
  return 0;
}

// RLE frames are laid out by hand: OpenEXR's reorder, predictor and run search go a byte at a
// time (a 256x192 dataset frame: 1.5-1.7 ms in OpenEXR, 0.43 ms here; exr_png_bench). The file is
// OpenEXR's, byte for byte: its own header, then one block per scanline (RLE's block height), each
// the OpenEXR RLE of the line's channels.

// The header OpenEXR writes for these channels at this size with RLE, made by OpenEXR itself
// (from a frame of zeros) once per layout.
// The map's entries are never erased, so the reference stays valid.
const std::string& RleHeader(const ExrChannels& channels, int width, int height) {
  std::string key = std::to_string(width) + "x" + std::to_string(height);
  for (const auto& [name, mat] : channels) key += "/" + name + ":" + std::to_string(mat.type());
  static std::mutex mutex;
  static std::map<std::string, std::string> headers;
  std::lock_guard<std::mutex> lock(mutex);
  auto it = headers.find(key);
  if (it == headers.end()) {
    ExrChannels zeros;
    for (const auto& [name, mat] : channels) zeros.emplace_back(name, cv::Mat::zeros(height, width, mat.type()));
    ExrWriteOptions library;
    library.compression = ExrCompression::kRle;
    library.openexr_rle = true;
    const std::string bytes = EncodeExr(zeros, library);
    const size_t end = HeaderEnd(bytes);
    HOILCD_CHECK_MSG(end > 0, "OpenEXR wrote a header HeaderEnd cannot read");
    it = headers.emplace(key, bytes.substr(0, end)).first;
  }
  return it->second;
}

// First q in [from, limit) where bytes q, q+1, q+2 (all before n) are equal, else limit.
size_t FirstTriple(const unsigned char* p, size_t from, size_t limit, size_t n) {
  size_t q = from;
#if defined(__SSE2__)
  // Sixteen positions at a time while q + 17 < n, so that every load stays inside the line.
  for (; q + 16 <= limit && q + 18 <= n; q += 16) {
    const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + q));
    const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + q + 1));
    const __m128i c = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + q + 2));
    const int mask = _mm_movemask_epi8(_mm_and_si128(_mm_cmpeq_epi8(a, b), _mm_cmpeq_epi8(b, c)));
    if (mask != 0) return q + static_cast<size_t>(__builtin_ctz(static_cast<unsigned>(mask)));
  }
#endif
  for (; q < limit; ++q) {
    if (q + 2 < n && p[q] == p[q + 1] && p[q + 1] == p[q + 2]) return q;
  }
  return limit;
}

// OpenEXR's run-length code: a run of 3 to 128 equal bytes is (length - 1, byte); bytes up to
// the next such run, at most 127, are (-count, bytes...). Writes at most n + n / 127 + 1 bytes
// to out; returns how many.
size_t RunLengths(const unsigned char* p, size_t n, unsigned char* out) {
  unsigned char* w = out;
  size_t s = 0;
  while (s < n) {
    size_t e = s + 1;
    const size_t run_limit = std::min(n, s + 128);
    while (e < run_limit && p[e] == p[s]) ++e;
    if (e - s >= 3) {
      *w++ = static_cast<unsigned char>(e - s - 1);
      *w++ = p[s];
      s = e;
      continue;
    }
    const size_t q = FirstTriple(p, e, std::min(n, s + 127), n);
    *w++ = static_cast<unsigned char>(-static_cast<int>(q - s));
    std::memcpy(w, p + s, q - s);
    w += q - s;
    s = q;
  }
  return static_cast<size_t>(w - out);
}

std::string EncodeRleExr(const ExrChannels& channels, int width, int height) {
  // Within a line, channels go in the order of OpenEXR's channel list: by name.
  std::vector<size_t> order(channels.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return channels[a].first < channels[b].first; });
  size_t line_bytes = 0;
  for (const auto& [name, mat] : channels) line_bytes += mat.elemSize() * static_cast<size_t>(width);

  const std::string& header = RleHeader(channels, width, height);
  const size_t table_at = header.size();
  const size_t block_capacity = 8 + line_bytes + line_bytes / 64 + 16;  // RunLengths adds <= n / 127 + 1
  std::string out(table_at + 8 * static_cast<size_t>(height) + static_cast<size_t>(height) * block_capacity, '\0');
  std::memcpy(out.data(), header.data(), header.size());
  size_t end = table_at + 8 * static_cast<size_t>(height);
  std::vector<unsigned char> line(line_bytes), split(line_bytes), coded(line_bytes);
  const auto put32 = [&](uint32_t v) {
    for (int i = 0; i < 4; ++i) out[end++] = static_cast<char>(v >> (8 * i));
  };
  for (int y = 0; y < height; ++y) {
    size_t at = 0;
    for (size_t k : order) {
      const cv::Mat& mat = channels[k].second;
      const size_t bytes = mat.elemSize() * static_cast<size_t>(width);
      std::memcpy(line.data() + at, mat.ptr(y), bytes);
      at += bytes;
    }
    // OpenEXR's preparation: even bytes then odd bytes, then each byte as its difference to the
    // one before, plus 128 (out of place, so that both loops run in vector lanes).
    const size_t half = (line_bytes + 1) / 2;
    for (size_t i = 0; i < half; ++i) split[i] = line[2 * i];
    for (size_t i = 0; i < line_bytes / 2; ++i) split[half + i] = line[2 * i + 1];
    coded[0] = split[0];
    for (size_t i = 1; i < line_bytes; ++i) coded[i] = static_cast<unsigned char>(split[i] - split[i - 1] + 128);
    const uint64_t offset = end;
    for (int i = 0; i < 8; ++i) out[table_at + 8 * static_cast<size_t>(y) + i] = static_cast<char>(offset >> (8 * i));
    put32(static_cast<uint32_t>(y));
    const size_t size_at = end;
    put32(0);
    const size_t size = RunLengths(coded.data(), line_bytes, reinterpret_cast<unsigned char*>(out.data() + end));
    // A line that does not shrink is stored as it is, as OpenEXR does.
    const bool raw = size >= line_bytes;
    if (raw) std::memcpy(out.data() + end, line.data(), line_bytes);
    const uint32_t stored = static_cast<uint32_t>(raw ? line_bytes : size);
    end += stored;
    for (int i = 0; i < 4; ++i) out[size_at + i] = static_cast<char>(stored >> (8 * i));
  }
  out.resize(end);
  return out;
}

// OpenEXR's RLE decode of one block: (n - 1, byte) runs and (-n, n bytes) literals into exactly
// `size` bytes; false when the block is malformed (the caller then lets OpenEXR report it).
bool UnRunLengths(const unsigned char* in, size_t in_size, unsigned char* out, size_t size) {
  size_t done = 0;
  for (size_t at = 0; at < in_size;) {
    const int count = static_cast<signed char>(in[at++]);
    if (count < 0) {
      const size_t n = static_cast<size_t>(-count);
      if (n > in_size - at || n > size - done) return false;
      std::memcpy(out + done, in + at, n);
      at += n;
      done += n;
    } else {
      const size_t n = static_cast<size_t>(count) + 1;
      if (at >= in_size || n > size - done) return false;
      std::memset(out + done, in[at++], n);
      done += n;
    }
  }
  return done == size;
}

// OpenEXR's predictor undone in place: byte i becomes byte i - 1 + byte i - 128 (mod 256), i.e. 128
// plus the prefix sum of (byte - 128). Sixteen bytes at a time: a prefix sum in four shifted adds,
// plus the running byte carried from the block before.
void UndoPredictor(unsigned char* p, size_t n) {
  unsigned char previous = 128;  // so that byte 0 stays as it is
  size_t i = 0;
#if defined(__SSE2__)
  __m128i carry = _mm_set1_epi8(static_cast<char>(previous));
  const __m128i bias = _mm_set1_epi8(static_cast<char>(128));
  for (; i + 16 <= n; i += 16) {
    __m128i v = _mm_sub_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p + i)), bias);
    v = _mm_add_epi8(v, _mm_slli_si128(v, 1));
    v = _mm_add_epi8(v, _mm_slli_si128(v, 2));
    v = _mm_add_epi8(v, _mm_slli_si128(v, 4));
    v = _mm_add_epi8(v, _mm_slli_si128(v, 8));
    v = _mm_add_epi8(v, carry);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(p + i), v);
    previous = p[i + 15];
    carry = _mm_set1_epi8(static_cast<char>(previous));
  }
#endif
  for (; i < n; ++i) p[i] = previous = static_cast<unsigned char>(previous + p[i] - 128);
}

// The lines of a single-part scanline RLE file read without OpenEXR's byte-at-a-time reorder and
// predictor (a dataset frame: ~4x faster), into `out`'s images (a subset of the header's channels,
// FLOAT or HALF into CV_32F, UINT into CV_32S). The header was parsed by OpenEXR already; false for
// any other layout or a malformed block, so that OpenEXR reads (or refuses) the file as before.
bool ReadRleLines(const std::string& bytes, const Imf::Header& header, ExrChannels* out) {
  // Version flags: tiled 0x02, deep 0x08, multi-part 0x10 (bits 9, 11, 12 of the version field).
  if (header.compression() != Imf::RLE_COMPRESSION || (static_cast<unsigned char>(bytes[5]) & 0x1A) != 0) return false;
  const Imath::Box2i dw = header.dataWindow();
  const size_t width = static_cast<size_t>(dw.max.x - dw.min.x + 1);
  const size_t height = static_cast<size_t>(dw.max.y - dw.min.y + 1);
  struct Part {
    size_t offset, bytes;
    Imf::PixelType type;
    cv::Mat* image;  // nullptr: not asked for
  };
  std::vector<Part> parts;
  size_t line_bytes = 0;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
    if (it.channel().xSampling != 1 || it.channel().ySampling != 1) return false;
    const size_t bytes_per_sample = it.channel().type == Imf::HALF ? 2 : 4;
    cv::Mat* image = nullptr;
    for (auto& [name, mat] : *out) image = name == it.name() ? &mat : image;
    parts.push_back({line_bytes, bytes_per_sample * width, it.channel().type, image});
    line_bytes += bytes_per_sample * width;
  }
  const size_t table = HeaderEnd(bytes);
  if (table == 0 || (bytes.size() - table) / 8 < height) return false;
  std::vector<unsigned char> coded(line_bytes), line(line_bytes);
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  for (size_t y = 0; y < height; ++y) {
    uint64_t offset = 0;
    std::memcpy(&offset, data + table + 8 * y, 8);
    int32_t line_y = 0, size = 0;
    if (offset < table || offset > bytes.size() - 8) return false;
    std::memcpy(&line_y, data + offset, 4);
    std::memcpy(&size, data + offset + 4, 4);
    if (line_y != dw.min.y + static_cast<int>(y) || size < 0 ||
        static_cast<uint64_t>(size) > bytes.size() - offset - 8 || static_cast<size_t>(size) > line_bytes) {
      return false;
    }
    const unsigned char* block = data + offset + 8;
    const bool raw = static_cast<size_t>(size) == line_bytes;  // stored as it is: it did not shrink
    if (!raw) {
      if (!UnRunLengths(block, static_cast<size_t>(size), coded.data(), line_bytes)) return false;
      UndoPredictor(coded.data(), line_bytes);
    }
    // Line byte k is byte k / 2 of the coded line's first half (k even) or of its second half (k
    // odd); parts start at even bytes (samples are 2 or 4 bytes), so only the asked-for ones are made.
    const size_t half = (line_bytes + 1) / 2;
    for (const Part& part : parts) {
      if (part.image == nullptr) continue;
      if (raw) {
        std::memcpy(line.data(), block + part.offset, part.bytes);
      } else {
        const unsigned char* even = coded.data() + part.offset / 2;
        const unsigned char* odd = coded.data() + half + part.offset / 2;
        for (size_t j = 0; j < part.bytes / 2; ++j) {
          line[2 * j] = even[j];
          line[2 * j + 1] = odd[j];
        }
      }
      void* row = part.image->ptr(static_cast<int>(y));
      if (part.type == Imf::HALF) {
        const cv::Mat halves(1, static_cast<int>(width), CV_16F, line.data());
        halves.convertTo(cv::Mat(1, static_cast<int>(width), CV_32F, row), CV_32F);
      } else {
        std::memcpy(row, line.data(), part.bytes);
      }
    }
  }
  return true;
}

}  // namespace

std::string EncodeExr(const ExrChannels& channels, const ExrWriteOptions& options) {
  HOILCD_CHECK(!channels.empty());
  HOILCD_CHECK(options.zip_level >= 1 && options.zip_level <= 9);
  const int width = channels.front().second.cols;
  const int height = channels.front().second.rows;
  for (const auto& [name, mat] : channels) {
    HOILCD_CHECK(mat.channels() == 1 && mat.cols == width && mat.rows == height && mat.isContinuous());
    PixelTypeOf(mat);  // one of the three types
  }
  if (options.compression == ExrCompression::kRle && !options.openexr_rle) return EncodeRleExr(channels, width, height);
  Imf::Header header(width, height);
  header.compression() = ToImf(options.compression);
  header.zipCompressionLevel() = options.zip_level;
  Imf::FrameBuffer fb;
  for (const auto& [name, mat] : channels) {
    const Imf::PixelType type = PixelTypeOf(mat);
    header.channels().insert(name, Imf::Channel(type));
    fb.insert(name, Imf::Slice(type, const_cast<char*>(mat.ptr<char>()), mat.elemSize(), mat.elemSize() * width));
  }
  StringOStream stream;
  {
    Imf::OutputFile file(stream, header, 1);  // one thread: frames are encoded in parallel instead
    file.setFrameBuffer(fb);
    file.writePixels(height);
  }
  return std::move(stream.data());
}

ExrChannels FrameExrChannels(const cv::Mat& temperature_c, const cv::Mat& ideal_c, const cv::Mat& depth_m,
                             const cv::Mat& instance, const cv::Mat& class_id) {
  HOILCD_CHECK(temperature_c.type() == CV_32F && ideal_c.type() == CV_32F && depth_m.type() == CV_32F &&
               instance.type() == CV_32S && class_id.type() == CV_32S);
  cv::Mat depth_half;
  depth_m.convertTo(depth_half, CV_16F);
  return {{"T", temperature_c}, {"T_true", ideal_c}, {"Z", depth_half}, {"id", instance}, {"class", class_id}};
}

namespace {

// OpenEXR reads through an IStream; this one reads the bytes already in memory (read once, and
// checked against the manifest by Dataset::ReadFile before they are decoded).
class StringIStream : public Imf::IStream {
 public:
  StringIStream(const std::string& bytes, const std::string& path) : Imf::IStream(path.c_str()), bytes_(bytes) {}
  bool read(char c[], int n) override {
    if (n < 0 || pos_ > bytes_.size() || static_cast<uint64_t>(n) > bytes_.size() - pos_) {
      throw std::runtime_error("unexpected end of file");  // what Imf's own file stream says
    }
    std::memcpy(c, bytes_.data() + pos_, static_cast<size_t>(n));
    pos_ += static_cast<uint64_t>(n);
    return pos_ < bytes_.size();
  }
  uint64_t tellg() override { return pos_; }
  void seekg(uint64_t pos) override { pos_ = pos; }  // past the end: the next read throws

 private:
  const std::string& bytes_;
  uint64_t pos_ = 0;
};

}  // namespace

ExrChannels ReadExr(const std::string& path, cv::Size size) { return DecodeExr(ReadFileBytes(path), path, size); }

ExrChannels DecodeExr(const std::string& bytes, const std::string& path, cv::Size size,
                      const std::vector<std::string>& only) {
  if (HeaderEnd(bytes) == 0) {
    throw InputError(path,
                     "not a readable OpenEXR file (damaged header: an attribute runs past the end or "
                     "disagrees with its type's size, or the data window is not 1 to " +
                         std::to_string(kMaxExrSidePx) + " px a side)");
  }
  try {
    StringIStream stream(bytes, path);
    Imf::InputFile file(stream, 1);
    const Imath::Box2i dw = file.header().dataWindow();
    const int64_t width = int64_t{dw.max.x} - dw.min.x + 1;
    const int64_t height = int64_t{dw.max.y} - dw.min.y + 1;
    if (width != size.width || height != size.height) {
      throw InputError(path, "expected a " + std::to_string(size.width) + "x" + std::to_string(size.height) +
                                 " px frame, the data window is " + std::to_string(width) + "x" +
                                 std::to_string(height));
    }
    int channels = 0;
    for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) ++channels;
    if (channels > kMaxExrChannels) {
      throw InputError(
          path, "expected at most " + std::to_string(kMaxExrChannels) + " channels, found " + std::to_string(channels));
    }
    // UINT channels are read into int32 (EncodeExr's bits) and then converted, the rest as FLOAT.
    ExrChannels out;
    Imf::FrameBuffer fb;
    for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
      if (!only.empty() && std::find(only.begin(), only.end(), it.name()) == only.end()) continue;
      const bool uint = it.channel().type == Imf::UINT;
      out.emplace_back(it.name(), cv::Mat(static_cast<int>(height), static_cast<int>(width), uint ? CV_32S : CV_32F));
    }
    if (!only.empty()) {
      ExrChannels ordered;
      for (const std::string& name : only) {
        const auto it = std::find_if(out.begin(), out.end(), [&](const auto& c) { return c.first == name; });
        if (it == out.end()) throw InputError(path, "has no channel '" + name + "'");
        ordered.push_back(*it);
      }
      out = std::move(ordered);
    }
    for (auto& [name, mat] : out) {
      char* base = mat.ptr<char>() - (dw.min.x + static_cast<ptrdiff_t>(dw.min.y) * width) * 4;
      fb.insert(name, Imf::Slice(mat.type() == CV_32S ? Imf::UINT : Imf::FLOAT, base, 4, 4 * width));
    }
    if (!ReadRleLines(bytes, file.header(), &out)) {
      file.setFrameBuffer(fb);
      file.readPixels(dw.min.y, dw.max.y);
    }
    for (auto& [name, mat] : out) {
      if (mat.type() == CV_32S) mat.convertTo(mat, CV_32F);
    }
    return out;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, std::string("not a readable OpenEXR file (") + e.what() + ")");
  }
}

ExrChannels ReadDatasetExr(const Dataset& dataset, int frame, const std::vector<std::string>& only) {
  dataset.RequireOutput("exr", "reading the EXR frames");
  const CameraIntrinsics& size = dataset.manifest().intrinsics;
  return DecodeExr(dataset.ReadFile("exr/" + FrameFileName(frame, "exr")), DatasetExrPath(dataset, frame),
                   {size.width, size.height}, only);
}

std::string DatasetExrPath(const Dataset& dataset, int frame) {
  return dataset.dir() + "/exr/" + FrameFileName(frame, "exr");
}

const cv::Mat& ExrChannel(const ExrChannels& channels, const std::string& name, const std::string& path) {
  for (const auto& [n, m] : channels)
    if (n == name) return m;
  throw InputError(path, "an EXR channel '" + name + "'");
}

}  // namespace hoilcd
