#include "hoilcd/bench/export/cdr_writer.h"

#include "hoilcd/core/util/error.h"

namespace hoilcd {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "CdrWriter writes the host's bytes as little-endian CDR");

CdrWriter::CdrWriter(size_t reserve_bytes) {
  buffer_.reserve(reserve_bytes + kHeaderBytes);
  // Representation identifier CDR_LE (0x0001), then two bytes of options.
  buffer_.append("\x00\x01\x00\x00", kHeaderBytes);
}

void CdrWriter::Align(size_t alignment) {
  const size_t offset = buffer_.size() - kHeaderBytes;
  const size_t pad = (alignment - offset % alignment) % alignment;
  buffer_.append(pad, '\0');
}

void CdrWriter::String(std::string_view s) {
  HOILCD_CHECK_MSG(s.size() < UINT32_MAX, "CDR string too long");
  Uint32(static_cast<uint32_t>(s.size() + 1));
  Put(s.data(), s.size());
  buffer_.push_back('\0');
}

void CdrWriter::Bytes(const void* data, size_t size) {
  HOILCD_CHECK_MSG(size <= UINT32_MAX, "CDR sequence too long");
  Uint32(static_cast<uint32_t>(size));
  Put(data, size);
}

void CdrWriter::Float64Sequence(const double* values, size_t count) {
  HOILCD_CHECK_MSG(count <= UINT32_MAX, "CDR sequence too long");
  Uint32(static_cast<uint32_t>(count));
  Float64Array(values, count);
}

void CdrWriter::Float64Array(const double* values, size_t count) {
  if (count == 0) return;
  Align(8);
  Put(values, count * sizeof(double));
}

}  // namespace hoilcd
