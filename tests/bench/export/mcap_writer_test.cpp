#include "hoilcd/bench/export/mcap_writer.h"

#include <cstring>

#include <gtest/gtest.h>
#include <libdeflate.h>

#include "hoilcd/bench/export/cdr_writer.h"
#include "hoilcd/bench/export/ros2_messages.h"

namespace hoilcd {
namespace {

constexpr char kMagic[] = "\x89MCAP0\r\n";

template <typename T>
T At(const std::string& bytes, size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof(T));
  return value;
}

uint32_t Crc(const std::string& bytes, size_t begin, size_t end) {
  return libdeflate_crc32(0, bytes.data() + begin, end - begin);
}

// A file with two channels and `messages` messages of 100 bytes, written in memory.
std::string WriteFile(const McapWriterOptions& options, int messages, McapStatistics* statistics = nullptr) {
  std::string file;
  McapWriter writer([&file](std::string_view bytes) { file.append(bytes.data(), bytes.size()); }, options);
  const uint16_t schema = writer.AddSchema("std_msgs/msg/Header", "ros2msg", "builtin_interfaces/Time stamp\n");
  const uint16_t a = writer.AddChannel(schema, "/a", "cdr", {{"k", "v"}});
  const uint16_t b = writer.AddChannel(schema, "/b", "cdr", {});
  for (int i = 0; i < messages; ++i) {
    writer.AddMessage(i % 3 == 0 ? b : a, 1000u * i, 1000u * i, std::string(100, static_cast<char>(i)));
  }
  const McapStatistics s = writer.Finish();
  if (statistics) *statistics = s;
  return file;
}

McapWriterOptions Uncompressed(uint64_t chunk_size_bytes) {
  McapWriterOptions options;
  options.compression = McapCompression::kNone;
  options.chunk_size_bytes = chunk_size_bytes;
  options.library = "test";
  return options;
}

TEST(McapWriter, FileStartsAndEndsWithTheMagicAndTheFooterPointsAtTheSummary) {
  McapStatistics statistics;
  const std::string file = WriteFile(Uncompressed(1000), 30, &statistics);
  ASSERT_GT(file.size(), 16u + 29u);
  EXPECT_EQ(file.substr(0, 8), std::string(kMagic, 8));
  EXPECT_EQ(file.substr(file.size() - 8), std::string(kMagic, 8));
  const size_t footer = file.size() - 8 - 29;  // opcode, length, two offsets, CRC
  EXPECT_EQ(file[footer], 0x02);
  EXPECT_EQ(At<uint64_t>(file, footer + 1), 20u);
  const uint64_t summary_start = At<uint64_t>(file, footer + 9);
  const uint64_t summary_offset_start = At<uint64_t>(file, footer + 17);
  EXPECT_LT(summary_start, summary_offset_start);
  EXPECT_EQ(file[summary_start], 0x03);         // the Schema group first
  EXPECT_EQ(file[summary_offset_start], 0x0E);  // a Summary Offset
  EXPECT_EQ(statistics.message_count, 30u);
  EXPECT_EQ(statistics.channel_message_counts.at(1), 20u);
  EXPECT_EQ(statistics.channel_message_counts.at(2), 10u);
  EXPECT_GT(statistics.chunk_count, 1u);  // 30 x ~130 bytes in chunks of 1000
  EXPECT_EQ(statistics.bytes, file.size());
}

TEST(McapWriter, TheFootersCrcCoversTheSummaryAndTheDataEndsCrcTheDataSection) {
  const std::string file = WriteFile(Uncompressed(1000), 30);
  const size_t footer = file.size() - 8 - 29;
  const uint64_t summary_start = At<uint64_t>(file, footer + 9);
  EXPECT_EQ(At<uint32_t>(file, footer + 25), Crc(file, summary_start, footer + 25));
  const size_t data_end = summary_start - 13;
  ASSERT_EQ(file[data_end], 0x0F);
  EXPECT_EQ(At<uint32_t>(file, data_end + 9), Crc(file, 0, data_end));
}

TEST(McapWriter, EachChunkCarriesTheCrcOfItsRecordsAndIsFollowedByItsMessageIndexes) {
  const std::string file = WriteFile(Uncompressed(1 << 20), 4);
  // magic, Header, Schema, two Channels, then the one chunk.
  size_t at = 8;
  for (int i = 0; i < 4; ++i) at += 9 + At<uint64_t>(file, at + 1);
  ASSERT_EQ(file[at], 0x06);
  const size_t content = at + 9;
  const uint64_t uncompressed = At<uint64_t>(file, content + 16);
  const uint32_t crc = At<uint32_t>(file, content + 24);
  EXPECT_EQ(At<uint32_t>(file, content + 28), 0u);  // compression "": uncompressed
  EXPECT_EQ(At<uint64_t>(file, content + 32), uncompressed);
  const size_t records = content + 40;
  EXPECT_EQ(crc, Crc(file, records, records + uncompressed));
  EXPECT_EQ(file[records], 0x05);  // the first message
  const size_t after = content + At<uint64_t>(file, at + 1);
  EXPECT_EQ(file[after], 0x07);  // its channels' message indexes
  EXPECT_EQ(At<uint16_t>(file, after + 9), 1u);
}

TEST(McapWriter, TheSameCallsGiveTheSameBytesAndZstdChunksAreSmaller) {
  McapWriterOptions zstd = Uncompressed(4096);
  zstd.compression = McapCompression::kZstd;
  EXPECT_EQ(WriteFile(zstd, 200), WriteFile(zstd, 200));
  EXPECT_LT(WriteFile(zstd, 200).size(), WriteFile(Uncompressed(4096), 200).size() / 2);
}

TEST(McapWriter, ParsesOnlyNoneAndZstd) {
  McapCompression c = McapCompression::kZstd;
  EXPECT_TRUE(ParseMcapCompression("none", &c));
  EXPECT_EQ(c, McapCompression::kNone);
  EXPECT_TRUE(ParseMcapCompression("zstd", &c));
  EXPECT_EQ(c, McapCompression::kZstd);
  EXPECT_FALSE(ParseMcapCompression("lz4", &c));
}

TEST(CdrWriter, AlignsEachPrimitiveToItsSizeAfterTheEncapsulationHeader) {
  CdrWriter w;
  w.Uint8(7);
  w.Float64(1.5);
  w.String("ab");
  w.Uint8(1);
  w.Uint32(9);
  const std::string& b = w.bytes();
  ASSERT_EQ(b.size(), 4u + 8 + 8 + 4 + 3 + 1 + 4);
  EXPECT_EQ(b.substr(0, 4), std::string("\x00\x01\x00\x00", 4));
  EXPECT_EQ(b[4], 7);
  EXPECT_EQ(At<double>(b, 4 + 8), 1.5);    // padded to offset 8 from the header's end
  EXPECT_EQ(At<uint32_t>(b, 4 + 16), 3u);  // length with the NUL
  EXPECT_EQ(b.substr(4 + 20, 3), std::string("ab\0", 3));
  EXPECT_EQ(b[4 + 23], 1);
  EXPECT_EQ(At<uint32_t>(b, 4 + 24), 9u);
}

TEST(Ros2Messages, DefinitionsListEachUsedTypeOnceAfterASeparator) {
  const std::string odometry = Ros2MessageDefinition("nav_msgs/Odometry");
  EXPECT_EQ(odometry.rfind("std_msgs/Header header\n", 0), 0u);
  const std::string separator = std::string(80, '=') + "\nMSG: ";
  for (const char* type : {"std_msgs/Header", "builtin_interfaces/Time", "geometry_msgs/PoseWithCovariance",
                           "geometry_msgs/Pose", "geometry_msgs/Point", "geometry_msgs/Quaternion",
                           "geometry_msgs/TwistWithCovariance", "geometry_msgs/Twist", "geometry_msgs/Vector3"}) {
    const std::string section = separator + type + "\n";
    EXPECT_NE(odometry.find(section), std::string::npos) << type;
    EXPECT_EQ(odometry.find(section), odometry.rfind(section)) << type;
  }
  EXPECT_EQ(Ros2SchemaName("sensor_msgs/Image"), "sensor_msgs/msg/Image");
}

TEST(Ros2Messages, AnImageIsItsHeaderFieldsThenTheRowsAsAByteSequence) {
  const uint16_t pixels[2] = {0x0102, 0x0304};
  const std::string m =
      SerializeImage({Ros2Time::FromNanoseconds(3'000'000'007u), "cam"}, 1, 2, "mono16", 4, pixels, 4);
  EXPECT_EQ(At<int32_t>(m, 4), 3);
  EXPECT_EQ(At<uint32_t>(m, 8), 7u);
  EXPECT_EQ(At<uint32_t>(m, 12), 4u);  // "cam" and its NUL
  EXPECT_EQ(m.substr(16, 4), std::string("cam\0", 4));
  EXPECT_EQ(At<uint32_t>(m, 20), 1u);  // height
  EXPECT_EQ(At<uint32_t>(m, 24), 2u);  // width
  EXPECT_EQ(m.substr(32, 7), std::string("mono16\0", 7));
  EXPECT_EQ(m[39], 0);                 // is_bigendian
  EXPECT_EQ(At<uint32_t>(m, 40), 4u);  // step
  EXPECT_EQ(At<uint32_t>(m, 44), 4u);  // data length
  EXPECT_EQ(At<uint16_t>(m, 48), 0x0102);
  EXPECT_EQ(m.size(), 52u);
}

}  // namespace
}  // namespace hoilcd
