// CDR serialisation of ROS 2 messages as rosbag2 stores them: XCDR1 ("plain CDR") little-endian,
// the 4-byte encapsulation header 00 01 00 00 first, each primitive aligned to its own size (at
// most 8) counted from the end of that header, strings as a uint32 length (with the NUL) then the
// bytes and a NUL, sequences as a uint32 element count then the elements, fixed arrays bare.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace hoilcd {

class CdrWriter {
 public:
  // Starts a message: clears the buffer and writes the encapsulation header. `reserve_bytes`:
  // the expected size, so an image is copied once.
  explicit CdrWriter(size_t reserve_bytes = 256);

  void Uint8(uint8_t v) { Put(&v, 1); }
  void Bool(bool v) { Uint8(v ? 1 : 0); }
  void Int32(int32_t v) { Aligned(&v, 4); }
  void Uint32(uint32_t v) { Aligned(&v, 4); }
  void Float64(double v) { Aligned(&v, 8); }
  void String(std::string_view s);
  // A sequence<uint8> (uint8[]): the count, then the bytes.
  void Bytes(const void* data, size_t size);
  // A sequence<float64> (float64[]): the count, then the values.
  void Float64Sequence(const double* values, size_t count);
  // A fixed array float64[N]: the values alone.
  void Float64Array(const double* values, size_t count);

  const std::string& bytes() const { return buffer_; }
  std::string Take() { return std::move(buffer_); }

 private:
  static constexpr size_t kHeaderBytes = 4;  // the encapsulation header, not counted in alignment
  void Put(const void* data, size_t size) { buffer_.append(static_cast<const char*>(data), size); }
  void Align(size_t alignment);
  void Aligned(const void* value, size_t size) {
    Align(size);
    Put(value, size);
  }

  std::string buffer_;
};

}  // namespace hoilcd
