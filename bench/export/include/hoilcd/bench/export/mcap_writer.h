// The MCAP container (https://mcap.dev/spec, major version 0): magic, Header, the Schema and Channel
// records, then the messages in Chunks (zstd or uncompressed), each Chunk followed by one Message
// Index record per channel in it, Data End with the data section's CRC-32; a summary section
// (Schemas, Channels, Statistics, Chunk Indexes), a Summary Offset per group, the Footer with the
// summary's CRC-32, magic. Bytes go out through a sink in order (no seeking), so a bag larger than
// memory streams to disk. The same calls give the same bytes: nothing depends on the clock.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace hoilcd {

enum class McapCompression { kNone, kZstd };

// "none" | "zstd" -> compression; false for anything else.
bool ParseMcapCompression(const std::string& text, McapCompression* compression);

struct McapWriterOptions {
  McapCompression compression = McapCompression::kZstd;  // of each chunk's records
  uint64_t chunk_size_bytes = 1u << 20;  // bytes: a chunk is closed once its uncompressed records reach this
  int zstd_level = 1;                    // zstd level (1: fastest of the standard levels)
  int threads = 1;                       // threads compressing chunks (0: every core); the same bytes at any count
  std::string profile = "ros2";          // the Header's profile
  std::string library;                   // the Header's library (the writer's name and version)
};

// What a finished file holds (the Statistics record's figures).
struct McapStatistics {
  uint64_t message_count = 0;
  uint32_t chunk_count = 0;
  uint64_t message_start_time = 0;  // ns, earliest log time
  uint64_t message_end_time = 0;    // ns, latest log time
  std::map<uint16_t, uint64_t> channel_message_counts;
  uint64_t bytes = 0;  // the file's size
};

class McapWriter {
 public:
  using Sink = std::function<void(std::string_view)>;
  // Writes the magic and the Header record to sink at once.
  McapWriter(Sink sink, McapWriterOptions options);

  // Schemas and channels, before the first message; ids count from 1 in the order added.
  uint16_t AddSchema(const std::string& name, const std::string& encoding, const std::string& data);
  uint16_t AddChannel(uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                      const std::map<std::string, std::string>& metadata);
  // A message on a channel; its sequence number counts the channel's messages from 0. Log times
  // need not increase, but a reader streams a file in order only when they do.
  void AddMessage(uint16_t channel_id, uint64_t log_time_ns, uint64_t publish_time_ns, std::string_view data);
  // Closes the last chunk, writes Data End, the summary, Summary Offsets, Footer and magic.
  McapStatistics Finish();

 private:
  struct Schema {
    uint16_t id;
    std::string record;  // the whole Schema record, as written in the data section
  };
  struct ClosedChunk {  // a full chunk waiting to be compressed and written
    std::string records;
    std::map<uint16_t, std::vector<std::pair<uint64_t, uint64_t>>> index;
    uint64_t start_time, end_time;
    std::unique_ptr<char[]> compressed;  // set by WriteClosedChunks (zstd)
    size_t compressed_size = 0;
    uint32_t crc = 0;  // of records
  };
  struct ChunkIndex {
    uint64_t start_time, end_time, offset, length, message_index_length, compressed_size, uncompressed_size;
    std::map<uint16_t, uint64_t> message_index_offsets;
  };

  void Emit(std::string_view bytes);  // to the sink, counted and (in the data section) CRC'd
  void CloseChunk();                  // the open chunk joins closed_, written once enough are there
  void WriteClosedChunks();           // compresses closed_ in parallel, then writes each with its indexes
  std::string SummaryGroups(std::vector<std::pair<uint8_t, std::pair<uint64_t, uint64_t>>>* offsets) const;

  Sink sink_;
  McapWriterOptions options_;
  uint64_t position_ = 0;        // bytes written so far
  uint32_t data_crc_ = 0;        // running CRC-32 of the data section (magic and Header included)
  bool in_data_section_ = true;  // until Data End
  bool finished_ = false;
  std::vector<Schema> schemas_;
  std::vector<std::string> channel_records_;
  std::vector<uint32_t> channel_sequence_;  // next sequence number per channel (index id - 1)
  // The open chunk: its records, each channel's (log time, offset in the records), its time span.
  std::string chunk_;
  std::map<uint16_t, std::vector<std::pair<uint64_t, uint64_t>>> chunk_index_;
  uint64_t chunk_start_time_ = 0, chunk_end_time_ = 0;
  std::vector<ClosedChunk> closed_;
  std::vector<ChunkIndex> chunk_indexes_;
  McapStatistics statistics_;
};

}  // namespace hoilcd
