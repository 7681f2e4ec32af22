// hoilcd's ByteTracker against the Python reference (ifzhang/ByteTrack) on recorded person
// detections of 400 rendered paper-room frames: tests/data/bytetrack_reference.txt, whose header
// says how the detections and the reference's tracks were recorded.
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hoilcd/core/tracking/byte_tracker.h"

namespace hoilcd {
namespace {

// The reference prints boxes with 5 decimals; hoilcd's boxes are floats (about 1e-5 px here).
constexpr double kBoxTolerancePx = 1e-3;

struct ReferenceFrame {
  int frame = 0;
  std::vector<Detection> detections;
  std::map<std::string, std::vector<Track>> tracks;  // "plus" / "cont" -> the reference's output
};

std::vector<ReferenceFrame> LoadFixture() {
  const std::string path = std::string(HOILCD_TEST_SOURCE_DIR) + "/tests/data/bytetrack_reference.txt";
  std::ifstream in(path);
  EXPECT_TRUE(in) << "cannot read " << path;
  std::vector<ReferenceFrame> frames;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string kind;
    int frame = 0;
    if (!(fields >> kind) || kind[0] == '#') continue;
    fields >> frame;
    if (kind == "frame") {
      frames.push_back({frame, {}, {{"plus", {}}, {"cont", {}}}});
      continue;
    }
    EXPECT_TRUE(!frames.empty() && frames.back().frame == frame) << line;
    if (frames.empty()) break;
    if (kind == "det") {
      Detection d;
      fields >> d.box.x >> d.box.y >> d.box.width >> d.box.height >> d.score;
      frames.back().detections.push_back(d);
    } else {
      Track t;
      fields >> t.id >> t.box.x >> t.box.y >> t.box.width >> t.box.height;
      frames.back().tracks.at(kind).push_back(t);
    }
    EXPECT_FALSE(fields.fail()) << line;
  }
  return frames;
}

bool SameBox(const cv::Rect2f& a, const cv::Rect2f& b) {
  return std::abs(a.x - b.x) <= kBoxTolerancePx && std::abs(a.y - b.y) <= kBoxTolerancePx &&
         std::abs(a.width - b.width) <= kBoxTolerancePx && std::abs(a.height - b.height) <= kBoxTolerancePx;
}

// Frames on which hoilcd's output (ids, order and boxes) differs from the reference's `kind`.
std::vector<int> FramesDifferingFromReference(IouConvention convention, const std::string& kind) {
  ByteTrackOptions options;
  options.iou_convention = convention;
  options.frame_rate_hz = 25;
  ByteTracker tracker(options);
  std::vector<int> differing;
  for (const ReferenceFrame& f : LoadFixture()) {
    const std::vector<Track> ours = tracker.Update(f.detections);
    const std::vector<Track>& theirs = f.tracks.at(kind);
    bool same = ours.size() == theirs.size();
    for (size_t i = 0; same && i < ours.size(); ++i) {
      same = ours[i].id == theirs[i].id && SameBox(ours[i].box, theirs[i].box);
    }
    if (!same) differing.push_back(f.frame);
  }
  return differing;
}

TEST(ByteTrackerReference, FixtureHoldsFourHundredFramesWithPeopleComingAndGoing) {
  const std::vector<ReferenceFrame> frames = LoadFixture();
  ASSERT_EQ(frames.size(), 400u);
  std::map<int, int> frames_per_id;
  size_t detections = 0;
  for (const ReferenceFrame& f : frames) {
    detections += f.detections.size();
    for (const Track& t : f.tracks.at("plus")) ++frames_per_id[t.id];
  }
  EXPECT_GT(detections, 400u);
  EXPECT_GE(frames_per_id.size(), 5u);
}

TEST(ByteTrackerReference, DefaultOptionsGiveTheReferencesIdsAndBoxesOnEveryFrame) {
  EXPECT_EQ(FramesDifferingFromReference(IouConvention::kPlusOnePixel, "plus"), std::vector<int>{});
}

TEST(ByteTrackerReference, ContinuousIouGivesTheReferenceWithContinuousIouOnEveryFrame) {
  EXPECT_EQ(FramesDifferingFromReference(IouConvention::kContinuous, "cont"), std::vector<int>{});
}

TEST(ByteTrackerReference, TheFixtureTellsTheTwoIouConventionsApart) {
  EXPECT_GT(FramesDifferingFromReference(IouConvention::kContinuous, "plus").size(), 10u);
}

}  // namespace
}  // namespace hoilcd
