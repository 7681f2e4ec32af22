#include "hoilcd/core/util/png.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include <libdeflate.h>

#include "hoilcd/core/util/error.h"

// Hand-written PNG container (signature, chunks, row filters; the PNG specification, sections 5,
// 9 and 11): no Debian library pairs PNG with libdeflate, whose inflate and deflate are what make
// this faster than libpng on zlib.
namespace hoilcd {
namespace {

constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr int kDeflateLevel = 1;
constexpr int kFilterSub = 1;

uint32_t BigEndian32(const unsigned char* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | uint32_t{p[3]};
}

void PutBigEndian32(uint32_t v, unsigned char* p) {
  p[0] = static_cast<unsigned char>(v >> 24);
  p[1] = static_cast<unsigned char>(v >> 16);
  p[2] = static_cast<unsigned char>(v >> 8);
  p[3] = static_cast<unsigned char>(v);
}

struct CompressorDeleter {
  void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};
struct DecompressorDeleter {
  void operator()(libdeflate_decompressor* d) const { libdeflate_free_decompressor(d); }
};

// One of each per thread, kept between frames (allocating a compressor costs more than a frame).
libdeflate_compressor* ThreadCompressor() {
  thread_local std::unique_ptr<libdeflate_compressor, CompressorDeleter> c(libdeflate_alloc_compressor(kDeflateLevel));
  HOILCD_CHECK_MSG(c != nullptr, "libdeflate_alloc_compressor failed");
  return c.get();
}

libdeflate_decompressor* ThreadDecompressor() {
  thread_local std::unique_ptr<libdeflate_decompressor, DecompressorDeleter> d(libdeflate_alloc_decompressor());
  HOILCD_CHECK_MSG(d != nullptr, "libdeflate_alloc_decompressor failed");
  return d.get();
}

// Writes a chunk's length, type, data (already at out + 8) and CRC; returns the chunk's size.
size_t FinishChunk(const char type[4], size_t length, unsigned char* out) {
  PutBigEndian32(static_cast<uint32_t>(length), out);
  std::memcpy(out + 4, type, 4);
  PutBigEndian32(libdeflate_crc32(0, out + 4, 4 + length), out + 8 + length);
  return 12 + length;
}

// The PNG filter's Paeth predictor.
inline int Paeth(int a, int b, int c) {
  const int p = a + b - c;
  const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  if (pa <= pb && pa <= pc) return a;
  return pb <= pc ? b : c;
}

// Reverses the filter of one row in place (`previous` is the row above, unfiltered, or zeros);
// bpp is 1 or 2 (8- or 16-bit grey), stride a multiple of it.
bool Unfilter(int filter, int bpp, size_t stride, const unsigned char* previous, unsigned char* row) {
  switch (filter) {
    case 0:
      return true;
    case 1:
      // A running sum per byte of a pixel, kept in registers: through memory, each byte would
      // wait for the store of the one before.
      if (bpp == 1) {
        unsigned char left = 0;
        for (size_t i = 0; i < stride; ++i) row[i] = left = static_cast<unsigned char>(row[i] + left);
      } else {
        unsigned char high = 0, low = 0;
        for (size_t i = 0; i < stride; i += 2) {
          row[i] = high = static_cast<unsigned char>(row[i] + high);
          row[i + 1] = low = static_cast<unsigned char>(row[i + 1] + low);
        }
      }
      return true;
    case 2:
      for (size_t i = 0; i < stride; ++i) row[i] = static_cast<unsigned char>(row[i] + previous[i]);
      return true;
    case 3:
      for (size_t i = 0; i < stride; ++i) {
        const int left = i >= static_cast<size_t>(bpp) ? row[i - bpp] : 0;
        row[i] = static_cast<unsigned char>(row[i] + ((left + previous[i]) >> 1));
      }
      return true;
    case 4:
      for (size_t i = 0; i < stride; ++i) {
        const bool first = i < static_cast<size_t>(bpp);
        row[i] = static_cast<unsigned char>(
            row[i] + Paeth(first ? 0 : row[i - bpp], previous[i], first ? 0 : previous[i - bpp]));
      }
      return true;
    default:
      return false;
  }
}

}  // namespace

bool PngSize(std::string_view bytes, uint32_t* width, uint32_t* height) {
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  if (bytes.size() < 24 || std::memcmp(p, kSignature, sizeof kSignature) != 0 || std::memcmp(p + 12, "IHDR", 4) != 0) {
    return false;
  }
  *width = BigEndian32(p + 16);
  *height = BigEndian32(p + 20);
  return true;
}

std::string EncodeGreyPng(const cv::Mat& image) {
  HOILCD_CHECK_MSG(!image.empty() && image.channels() == 1 && (image.depth() == CV_8U || image.depth() == CV_16U),
                   "EncodeGreyPng takes a non-empty 1-channel CV_8U or CV_16U image");
  const int bpp = image.depth() == CV_16U ? 2 : 1;
  const size_t stride = static_cast<size_t>(image.cols) * bpp;
  thread_local std::vector<unsigned char> filtered;
  filtered.resize((stride + 1) * static_cast<size_t>(image.rows));
  for (int y = 0; y < image.rows; ++y) {
    unsigned char* out = filtered.data() + (stride + 1) * static_cast<size_t>(y);
    out[0] = kFilterSub;
    if (bpp == 1) {
      const uint8_t* in = image.ptr<uint8_t>(y);
      out[1] = in[0];
      for (int x = 1; x < image.cols; ++x) out[1 + x] = static_cast<unsigned char>(in[x] - in[x - 1]);
    } else {  // big-endian samples, each byte minus the same byte of the sample to its left
      const uint16_t* in = image.ptr<uint16_t>(y);
      unsigned previous_high = 0, previous_low = 0;
      for (int x = 0; x < image.cols; ++x) {
        const unsigned high = in[x] >> 8, low = in[x] & 0xffu;
        out[1 + 2 * x] = static_cast<unsigned char>(high - previous_high);
        out[2 + 2 * x] = static_cast<unsigned char>(low - previous_low);
        previous_high = high, previous_low = low;
      }
    }
  }
  libdeflate_compressor* compressor = ThreadCompressor();
  const size_t bound = libdeflate_zlib_compress_bound(compressor, filtered.size());
  const size_t ihdr_at = sizeof kSignature, idat_at = ihdr_at + 12 + 13;
  std::string png(idat_at + 12 + bound + 12, '\0');
  auto* out = reinterpret_cast<unsigned char*>(png.data());
  std::memcpy(out, kSignature, sizeof kSignature);
  unsigned char* ihdr = out + ihdr_at + 8;
  PutBigEndian32(static_cast<uint32_t>(image.cols), ihdr);
  PutBigEndian32(static_cast<uint32_t>(image.rows), ihdr + 4);
  ihdr[8] = static_cast<unsigned char>(8 * bpp);  // bit depth; colour type, compression, filter, interlace 0
  FinishChunk("IHDR", 13, out + ihdr_at);
  const size_t deflated =
      libdeflate_zlib_compress(compressor, filtered.data(), filtered.size(), out + idat_at + 8, bound);
  HOILCD_CHECK_MSG(deflated > 0, "libdeflate_zlib_compress: " << filtered.size() << " bytes did not fit its bound");
  const size_t iend_at = idat_at + FinishChunk("IDAT", deflated, out + idat_at);
  png.resize(iend_at + FinishChunk("IEND", 0, out + iend_at));
  return png;
}

bool DecodeGreyPng(std::string_view bytes, int width, int height, int type, cv::Mat* image) {
  HOILCD_CHECK(image != nullptr);
  if (width <= 0 || height <= 0 || (type != CV_8UC1 && type != CV_16UC1)) return false;
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  const size_t n = bytes.size();
  if (n < sizeof kSignature || std::memcmp(p, kSignature, sizeof kSignature) != 0) return false;
  const int bpp = type == CV_16UC1 ? 2 : 1;
  // Walks the chunks, checking each one's CRC; gathers the IDAT data.
  thread_local std::string gathered;
  gathered.clear();
  const unsigned char* only_idat = nullptr;  // the IDAT data if there is exactly one chunk of it
  size_t only_idat_length = 0, idat_chunks = 0;
  bool header = false, end = false;
  for (size_t at = sizeof kSignature; !end;) {
    if (n - at < 12) return false;
    const uint32_t length = BigEndian32(p + at);
    if (length > n - at - 12) return false;
    const unsigned char* chunk_type = p + at + 4;
    const unsigned char* data = p + at + 8;
    if (libdeflate_crc32(0, chunk_type, 4 + length) != BigEndian32(data + length)) return false;
    if (!header) {  // IHDR first: the size, depth and layout asked for
      if (std::memcmp(chunk_type, "IHDR", 4) != 0 || length != 13) return false;
      if (BigEndian32(data) != static_cast<uint32_t>(width) || BigEndian32(data + 4) != static_cast<uint32_t>(height) ||
          data[8] != 8 * bpp || data[9] != 0 || data[10] != 0 || data[11] != 0 || data[12] != 0) {
        return false;
      }
      header = true;
    } else if (std::memcmp(chunk_type, "IDAT", 4) == 0) {
      if (++idat_chunks == 1) only_idat = data, only_idat_length = length;
      gathered.append(reinterpret_cast<const char*>(data), length);
    } else if (std::memcmp(chunk_type, "IEND", 4) == 0) {
      end = true;
    } else {
      return false;  // any other chunk, even an ancillary one: OpenCV knows what it means
    }
    at += 12 + static_cast<size_t>(length);
  }
  if (idat_chunks == 0) return false;
  const size_t stride = static_cast<size_t>(width) * bpp;
  thread_local std::vector<unsigned char> raw;
  raw.resize((stride + 1) * static_cast<size_t>(height));
  const auto* deflated = idat_chunks == 1 ? only_idat : reinterpret_cast<const unsigned char*>(gathered.data());
  const size_t deflated_length = idat_chunks == 1 ? only_idat_length : gathered.size();
  // libdeflate ignores the zlib window size, which zlib (libpng's) enforces: a stream declaring a
  // window under 32 kB is left to OpenCV, and so is one with bytes after its checksum.
  if (deflated_length < 2 || (deflated[0] >> 4) != 7) return false;
  size_t used = 0;
  // Without an actual-output argument libdeflate succeeds only on exactly raw.size() bytes.
  if (libdeflate_zlib_decompress_ex(ThreadDecompressor(), deflated, deflated_length, raw.data(), raw.size(), &used,
                                    nullptr) != LIBDEFLATE_SUCCESS ||
      used != deflated_length) {
    return false;
  }
  thread_local std::vector<unsigned char> zeros;
  zeros.assign(stride, 0);
  cv::Mat decoded(height, width, type);
  const unsigned char* previous = zeros.data();
  for (int y = 0; y < height; ++y) {
    unsigned char* row = raw.data() + (stride + 1) * static_cast<size_t>(y);
    if (!Unfilter(row[0], bpp, stride, previous, row + 1)) return false;
    previous = row + 1;
    if (bpp == 1) {
      std::memcpy(decoded.ptr<uint8_t>(y), row + 1, stride);
    } else {
      uint16_t* out = decoded.ptr<uint16_t>(y);
      for (int x = 0; x < width; ++x) out[x] = static_cast<uint16_t>((row[1 + 2 * x] << 8) | row[2 + 2 * x]);
    }
  }
  *image = decoded;
  return true;
}

}  // namespace hoilcd
