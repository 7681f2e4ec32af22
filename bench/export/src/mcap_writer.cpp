// No Debian package writes MCAP, so this writer is hand-written from the specification.
#include "hoilcd/bench/export/mcap_writer.h"

#include <algorithm>

#include <libdeflate.h>
#include <zstd.h>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/parallel.h"

namespace hoilcd {
namespace {

constexpr char kMagic[] = "\x89MCAP0\r\n";
constexpr size_t kMagicBytes = 8;

enum Opcode : uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kStatistics = 0x0B,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

// Little-endian record fields (the spec's serialisation) appended to a string.
class Fields {
 public:
  Fields& U8(uint8_t v) { return Raw(&v, 1); }
  Fields& U16(uint16_t v) { return Raw(&v, 2); }
  Fields& U32(uint32_t v) { return Raw(&v, 4); }
  Fields& U64(uint64_t v) { return Raw(&v, 8); }
  Fields& Str(std::string_view s) {  // uint32 byte length, then the bytes
    U32(static_cast<uint32_t>(s.size()));
    return Raw(s.data(), s.size());
  }
  Fields& Raw(const void* data, size_t size) {
    text_.append(static_cast<const char*>(data), size);
    return *this;
  }
  size_t size() const { return text_.size(); }
  std::string& text() { return text_; }

 private:
  std::string text_;
};
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "Fields writes the host's bytes as little-endian");

// opcode, uint64 content length, content.
std::string Record(uint8_t opcode, const std::string& content) {
  Fields f;
  f.U8(opcode).U64(content.size()).Raw(content.data(), content.size());
  return std::move(f.text());
}

// Map<K, V> as the spec serialises it: uint32 byte length of the entries, then the entries.
template <typename Write>
void MapField(Fields* f, const Write& write_entries) {
  Fields entries;
  write_entries(&entries);
  f->U32(static_cast<uint32_t>(entries.size())).Raw(entries.text().data(), entries.size());
}

uint32_t Crc32(uint32_t crc, std::string_view bytes) { return libdeflate_crc32(crc, bytes.data(), bytes.size()); }

// zstd's frame of bytes into a buffer of its own (not zero-filled first); returns its size.
size_t ZstdCompress(const std::string& bytes, int level, std::unique_ptr<char[]>* out) {
  const size_t bound = ZSTD_compressBound(bytes.size());
  out->reset(new char[bound]);
  const size_t n = ZSTD_compress(out->get(), bound, bytes.data(), bytes.size(), level);
  HOILCD_CHECK_MSG(!ZSTD_isError(n), "zstd: " << ZSTD_getErrorName(n));
  return n;
}

}  // namespace

bool ParseMcapCompression(const std::string& text, McapCompression* compression) {
  if (text == "zstd")
    *compression = McapCompression::kZstd;
  else if (text == "none")
    *compression = McapCompression::kNone;
  else
    return false;
  return true;
}

McapWriter::McapWriter(Sink sink, McapWriterOptions options) : sink_(std::move(sink)), options_(std::move(options)) {
  HOILCD_CHECK(options_.chunk_size_bytes > 0);
  Emit(std::string_view(kMagic, kMagicBytes));
  Fields header;
  header.Str(options_.profile).Str(options_.library);
  Emit(Record(kHeader, header.text()));
}

void McapWriter::Emit(std::string_view bytes) {
  if (in_data_section_) data_crc_ = Crc32(data_crc_, bytes);
  position_ += bytes.size();
  sink_(bytes);
}

uint16_t McapWriter::AddSchema(const std::string& name, const std::string& encoding, const std::string& data) {
  HOILCD_CHECK_MSG(statistics_.message_count == 0, "McapWriter: schemas are added before the first message");
  const uint16_t id = static_cast<uint16_t>(schemas_.size() + 1);
  Fields f;
  f.U16(id).Str(name).Str(encoding).Str(data);
  schemas_.push_back({id, Record(kSchema, f.text())});
  Emit(schemas_.back().record);
  return id;
}

uint16_t McapWriter::AddChannel(uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                                const std::map<std::string, std::string>& metadata) {
  HOILCD_CHECK_MSG(statistics_.message_count == 0, "McapWriter: channels are added before the first message");
  HOILCD_CHECK_MSG(schema_id >= 1 && schema_id <= schemas_.size(), "McapWriter: unknown schema " << schema_id);
  const uint16_t id = static_cast<uint16_t>(channel_records_.size() + 1);
  Fields f;
  f.U16(id).U16(schema_id).Str(topic).Str(message_encoding);
  MapField(&f, [&](Fields* e) {
    for (const auto& [key, value] : metadata) e->Str(key).Str(value);  // std::map: sorted, as the spec asks
  });
  channel_records_.push_back(Record(kChannel, f.text()));
  channel_sequence_.push_back(0);
  Emit(channel_records_.back());
  return id;
}

void McapWriter::AddMessage(uint16_t channel_id, uint64_t log_time_ns, uint64_t publish_time_ns,
                            std::string_view data) {
  HOILCD_CHECK_MSG(!finished_, "McapWriter: message after Finish");
  HOILCD_CHECK_MSG(channel_id >= 1 && channel_id <= channel_records_.size(),
                   "McapWriter: unknown channel " << channel_id);
  if (chunk_.empty()) chunk_start_time_ = chunk_end_time_ = log_time_ns;
  chunk_start_time_ = std::min(chunk_start_time_, log_time_ns);
  chunk_end_time_ = std::max(chunk_end_time_, log_time_ns);
  chunk_index_[channel_id].emplace_back(log_time_ns, chunk_.size());
  Fields f;
  f.U8(kMessage).U64(2 + 4 + 8 + 8 + data.size());
  f.U16(channel_id).U32(channel_sequence_[channel_id - 1u]++).U64(log_time_ns).U64(publish_time_ns);
  chunk_ += f.text();
  chunk_.append(data.data(), data.size());
  if (statistics_.message_count == 0) statistics_.message_start_time = statistics_.message_end_time = log_time_ns;
  statistics_.message_start_time = std::min(statistics_.message_start_time, log_time_ns);
  statistics_.message_end_time = std::max(statistics_.message_end_time, log_time_ns);
  ++statistics_.message_count;
  ++statistics_.channel_message_counts[channel_id];
  if (chunk_.size() >= options_.chunk_size_bytes) CloseChunk();
}

void McapWriter::CloseChunk() {
  if (chunk_.empty()) return;
  closed_.push_back({std::move(chunk_), std::move(chunk_index_), chunk_start_time_, chunk_end_time_, nullptr, 0, 0});
  chunk_ = std::string();
  chunk_.reserve(options_.chunk_size_bytes + (options_.chunk_size_bytes >> 2));
  chunk_index_.clear();
  if (closed_.size() >= static_cast<size_t>(2 * ResolveThreadCount(options_.threads))) WriteClosedChunks();
}

void McapWriter::WriteClosedChunks() {
  const bool zstd = options_.compression == McapCompression::kZstd;
  ParallelFor(static_cast<int64_t>(closed_.size()), options_.threads, [&](int64_t i) {
    ClosedChunk& c = closed_[static_cast<size_t>(i)];
    c.crc = Crc32(0, c.records);
    if (zstd) c.compressed_size = ZstdCompress(c.records, options_.zstd_level, &c.compressed);
  });
  for (const ClosedChunk& c : closed_) {
    const std::string_view records = zstd ? std::string_view(c.compressed.get(), c.compressed_size) : c.records;
    // The Chunk record's fields, then its records as they are (no copy).
    Fields f;
    f.U64(c.start_time).U64(c.end_time).U64(c.records.size()).U32(c.crc).Str(zstd ? "zstd" : "").U64(records.size());
    Fields head;
    head.U8(kChunk).U64(f.size() + records.size()).Raw(f.text().data(), f.size());
    const uint64_t length = head.size() + records.size();
    ChunkIndex index{c.start_time, c.end_time, position_, length, 0, records.size(), c.records.size(), {}};
    Emit(head.text());
    Emit(records);
    const uint64_t indexes_start = position_;
    for (const auto& [channel, entries] : c.index) {  // by channel id
      Fields m;
      m.U16(channel);
      MapField(&m, [&](Fields* e) {
        for (const auto& [time, offset] : entries) e->U64(time).U64(offset);
      });
      index.message_index_offsets[channel] = position_;
      Emit(Record(kMessageIndex, m.text()));
    }
    index.message_index_length = position_ - indexes_start;
    chunk_indexes_.push_back(std::move(index));
    ++statistics_.chunk_count;
  }
  closed_.clear();
}

// The summary section's records, group by group; offsets gets (opcode, (start, length)) per group,
// starts counted from the summary's start.
std::string McapWriter::SummaryGroups(std::vector<std::pair<uint8_t, std::pair<uint64_t, uint64_t>>>* offsets) const {
  std::string summary;
  const auto group = [&](uint8_t opcode, const std::string& records) {
    if (records.empty()) return;
    offsets->push_back({opcode, {summary.size(), records.size()}});
    summary += records;
  };
  std::string schemas, channels, chunk_indexes;
  for (const Schema& s : schemas_) schemas += s.record;
  for (const std::string& c : channel_records_) channels += c;
  Fields st;
  st.U64(statistics_.message_count).U16(static_cast<uint16_t>(schemas_.size()));
  st.U32(static_cast<uint32_t>(channel_records_.size())).U32(0).U32(0).U32(statistics_.chunk_count);
  st.U64(statistics_.message_start_time).U64(statistics_.message_end_time);
  MapField(&st, [&](Fields* e) {
    for (const auto& [channel, count] : statistics_.channel_message_counts) e->U16(channel).U64(count);
  });
  for (const ChunkIndex& c : chunk_indexes_) {
    Fields f;
    f.U64(c.start_time).U64(c.end_time).U64(c.offset).U64(c.length);
    MapField(&f, [&](Fields* e) {
      for (const auto& [channel, offset] : c.message_index_offsets) e->U16(channel).U64(offset);
    });
    f.U64(c.message_index_length).Str(options_.compression == McapCompression::kZstd ? "zstd" : "");
    f.U64(c.compressed_size).U64(c.uncompressed_size);
    chunk_indexes += Record(kChunkIndex, f.text());
  }
  group(kSchema, schemas);
  group(kChannel, channels);
  group(kStatistics, Record(kStatistics, st.text()));
  group(kChunkIndex, chunk_indexes);
  return summary;
}

McapStatistics McapWriter::Finish() {
  HOILCD_CHECK_MSG(!finished_, "McapWriter::Finish twice");
  CloseChunk();
  WriteClosedChunks();
  finished_ = true;
  Fields data_end;
  data_end.U32(data_crc_);
  in_data_section_ = false;
  Emit(Record(kDataEnd, data_end.text()));
  const uint64_t summary_start = position_;
  std::vector<std::pair<uint8_t, std::pair<uint64_t, uint64_t>>> groups;
  std::string summary = SummaryGroups(&groups);
  const uint64_t summary_offset_start = summary_start + summary.size();
  for (const auto& [opcode, span] : groups) {
    Fields f;
    f.U8(opcode).U64(summary_start + span.first).U64(span.second);
    summary += Record(kSummaryOffset, f.text());
  }
  // The footer's CRC covers the summary, the summary offsets and the footer up to the CRC itself.
  Fields footer;
  footer.U8(kFooter).U64(8 + 8 + 4).U64(summary_start).U64(summary_offset_start);
  const uint32_t summary_crc = Crc32(Crc32(0, summary), footer.text());
  footer.U32(summary_crc).Raw(kMagic, kMagicBytes);
  Emit(summary);
  Emit(footer.text());
  statistics_.bytes = position_;
  return statistics_;
}

}  // namespace hoilcd
