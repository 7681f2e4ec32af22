#include "hoilcd/core/tracking/byte_tracker.h"

#include <map>
#include <optional>
#include <set>

#include <gtest/gtest.h>

#include "hoilcd/core/util/random.h"
#include "option_properties.h"

namespace hoilcd {
namespace {

double Iou(const cv::Rect2f& a, const cv::Rect2f& b) { return 1.0 - IouDistance({a}, {b})[0][0]; }

// The output track that best overlaps `truth`, if any overlaps by IoU > 0.5.
std::optional<int> TrackIdOf(const std::vector<Track>& tracks, const cv::Rect2f& truth) {
  std::optional<int> best;
  double best_iou = 0.5;
  for (const Track& t : tracks) {
    const double iou = Iou(t.box, truth);
    if (iou > best_iou) {
      best_iou = iou;
      best = t.id;
    }
  }
  return best;
}

struct ScriptedPerson {
  char name;
  int first_frame, last_frame;  // visible in [first, last], except in the gap
  int gap_begin, gap_end;       // not detected in [gap_begin, gap_end)
  cv::Point2f start, velocity;  // px, px/frame
  cv::Size2f size;
  cv::Rect2f BoxAt(int frame) const {
    return {start.x + velocity.x * frame, start.y + velocity.y * frame, size.width, size.height};
  }
  bool Visible(int frame) const {
    return frame >= first_frame && frame <= last_frame && !(frame >= gap_begin && frame < gap_end);
  }
};

// A and B walk across each other (A left to right, B right to left, 20 px apart vertically);
// C walks slowly, fades to a low score, disappears for 10 frames and comes back; D appears late.
TEST(ByteTracker, IdsSurviveCrossingAndAnOcclusionGapAndANewPersonGetsANewId) {
  const std::vector<ScriptedPerson> people = {
      {'A', 1, 70, 0, 0, {10, 40}, {3, 0}, {30, 60}},
      {'B', 1, 70, 0, 0, {220, 60}, {-3, 0}, {30, 60}},
      {'C', 1, 70, 30, 40, {100, 125}, {1, 0}, {24, 48}},
      {'D', 45, 70, 0, 0, {10, 115}, {0, 0}, {28, 56}},
  };
  ByteTracker tracker;
  std::map<char, std::set<int>> ids_of;
  std::set<int> ids_seen_before_d;
  for (int frame = 1; frame <= 70; ++frame) {
    std::vector<Detection> detections;
    for (const ScriptedPerson& p : people) {
      if (!p.Visible(frame)) continue;
      Rng rng = KeyedRng(3, "test.bytetrack", frame, p.name);
      cv::Rect2f box = p.BoxAt(frame);
      box.x += static_cast<float>(rng.Uniform(-1, 1));
      box.y += static_cast<float>(rng.Uniform(-1, 1));
      // C is half hidden just before the gap: only a low-score detection.
      const float score = (p.name == 'C' && frame >= 26 && frame < 30) ? 0.3f : 0.9f;
      detections.push_back({box, score});
    }
    const std::vector<Track> tracks = tracker.Update(detections);
    for (const ScriptedPerson& p : people) {
      const std::optional<int> id = TrackIdOf(tracks, p.BoxAt(frame));
      if (!p.Visible(frame)) {
        if (p.name == 'C' && frame >= p.gap_begin && frame < p.gap_end) {
          EXPECT_EQ(id, std::nullopt) << "lost tracks are not output, frame " << frame;
        }
        continue;
      }
      // A new person is confirmed on its second frame; everybody else is tracked every frame.
      if (p.name == 'D' && frame == p.first_frame) {
        EXPECT_EQ(id, std::nullopt) << "an unconfirmed track is not output";
        continue;
      }
      ASSERT_TRUE(id.has_value()) << p.name << " untracked at frame " << frame;
      ids_of[p.name].insert(*id);
      if (p.name != 'D' && frame < people[3].first_frame) ids_seen_before_d.insert(*id);
    }
  }
  for (char name : {'A', 'B', 'C', 'D'}) {
    EXPECT_EQ(ids_of[name].size(), 1u) << name << " changed id";
  }
  EXPECT_EQ(ids_seen_before_d.size(), 3u);
  EXPECT_EQ(ids_seen_before_d.count(*ids_of['D'].begin()), 0u) << "D must get a new id";
  EXPECT_EQ(*ids_of['D'].begin(), 4);
}

TEST(ByteTracker, LowScoreDetectionsNeverStartTracks) {
  ByteTracker tracker;
  for (int frame = 1; frame <= 5; ++frame) {
    EXPECT_TRUE(tracker.Update({{{50, 50, 20, 40}, 0.45f}}).empty());
  }
}

TEST(ByteTracker, ASingleFrameSpuriousDetectionIsNeverOutput) {
  ByteTracker tracker;
  tracker.Update({{{50, 50, 20, 40}, 0.9f}});  // frame 1: confirmed at once
  EXPECT_EQ(tracker.Update({{{50, 50, 20, 40}, 0.9f}, {{150, 50, 20, 40}, 0.9f}}).size(), 1u);
  EXPECT_EQ(tracker.Update({{{50, 50, 20, 40}, 0.9f}}).size(), 1u);
  // The spurious box returns later: it starts over as a fresh unconfirmed track.
  EXPECT_EQ(tracker.Update({{{50, 50, 20, 40}, 0.9f}, {{150, 50, 20, 40}, 0.9f}}).size(), 1u);
}

TEST(ByteTracker, DroppedTracksDoNotCarryOverAndIdsCountOn) {
  ByteTracker tracker;
  const Detection d{{50, 50, 20, 40}, 0.9f};
  const int first_id = tracker.Update({d}).at(0).id;
  EXPECT_EQ(tracker.Update({d}).at(0).id, first_id);
  tracker.DropTracks();
  // The same box after the drop is a new, unconfirmed track: nothing out, then a new id.
  EXPECT_TRUE(tracker.Update({d}).empty());
  const std::vector<Track> again = tracker.Update({d});
  ASSERT_EQ(again.size(), 1u);
  EXPECT_GT(again[0].id, first_id);
}

TEST(ByteTracker, HighDetectionsBetweenLowAndNewTrackThresholdsKeepButDoNotStartTracks) {
  ByteTracker tracker;
  EXPECT_TRUE(tracker.Update({{{50, 50, 20, 40}, 0.55f}}).empty());
  EXPECT_TRUE(tracker.Update({{{50, 50, 20, 40}, 0.55f}}).empty());
}

TEST(ByteTracker, TrackLostLongerThanTheBufferComesBackWithANewId) {
  ByteTrackOptions options;
  options.track_buffer_frames = 6;
  options.frame_rate_hz = 30;
  ByteTracker tracker(options);
  EXPECT_EQ(tracker.max_time_lost_frames(), 6);
  const Detection d{{50, 50, 20, 40}, 0.9f};
  const int first_id = tracker.Update({d}).at(0).id;
  tracker.Update({d});
  for (int k = 0; k < 6; ++k) tracker.Update({});  // lost for 6 frames: still kept
  EXPECT_EQ(tracker.Update({d}).at(0).id, first_id);
  for (int k = 0; k < 7; ++k) tracker.Update({});  // 7 frames: removed
  EXPECT_TRUE(tracker.Update({d}).empty());        // new, unconfirmed
  const std::vector<Track> again = tracker.Update({d});
  ASSERT_EQ(again.size(), 1u);
  EXPECT_NE(again[0].id, first_id);
}

TEST(ByteTracker, BufferScalesWithFrameRateAsPython) {
  ByteTrackOptions options;  // 25 Hz, 30 frames -> int(25 / 30 * 30) = 25
  EXPECT_EQ(ByteTracker(options).max_time_lost_frames(), 25);
}

TEST(ByteTrackOptions, CheckNamesTheBadField) {
  EXPECT_EQ(ByteTrackOptions{}.Check(), "");
  ByteTrackOptions bad;
  bad.track_low_thresh = 0.7;
  EXPECT_NE(bad.Check().find("track_low_thresh"), std::string::npos);
  bad = {};
  bad.match_thresh = 0;
  EXPECT_NE(bad.Check().find("match_thresh"), std::string::npos);
  bad = {};
  bad.frame_rate_hz = -1;
  EXPECT_NE(bad.Check().find("frame_rate_hz"), std::string::npos);
  EXPECT_THROW(ByteTracker{bad}, std::logic_error);
}

TEST(ByteTrackOptions, HoldThePythonReferencesDefaultsFromTheirTableAndEveryBoundIsChecked) {
  const ByteTrackOptions o;
  EXPECT_EQ(o.track_high_thresh, 0.5);
  EXPECT_EQ(o.track_low_thresh, 0.1);
  EXPECT_EQ(o.new_track_thresh, 0.6);
  EXPECT_EQ(o.match_thresh, 0.8);
  EXPECT_EQ(o.second_match_thresh, 0.5);
  EXPECT_EQ(o.unconfirmed_match_thresh, 0.7);
  EXPECT_EQ(o.track_buffer_frames, 30);
  EXPECT_TRUE(o.fuse_score);
  EXPECT_EQ(o.iou_convention, IouConvention::kPlusOnePixel);
  ExpectConstructedHoldsTheTableDefaults<ByteTrackOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<ByteTrackOptions>(), 15);
}

TEST(IouDistance, IsOneMinusIntersectionOverUnion) {
  const auto d = IouDistance({{0, 0, 10, 10}}, {{5, 0, 10, 10}, {20, 20, 5, 5}, {0, 0, 10, 10}});
  EXPECT_NEAR(d[0][0], 1.0 - 50.0 / 150.0, 1e-9);
  EXPECT_DOUBLE_EQ(d[0][1], 1.0);
  EXPECT_DOUBLE_EQ(d[0][2], 0.0);
}

TEST(IouDistance, PlusOnePixelCountsInclusivePixelCornersAsCythonBbox) {
  // (x1, y1, x2, y2) = (0, 0, 10, 10) and (5, 0, 15, 10): 6 x 11 shared of 11 x 11 each.
  const auto d =
      IouDistance({{0, 0, 10, 10}}, {{5, 0, 10, 10}, {10, 0, 5, 5}, {11, 0, 5, 5}}, IouConvention::kPlusOnePixel);
  EXPECT_NEAR(d[0][0], 1.0 - 66.0 / (121.0 + 121.0 - 66.0), 1e-12);
  EXPECT_NEAR(d[0][1], 1.0 - 6.0 / (121.0 + 36.0 - 6.0), 1e-12);  // touching boxes share 1 px
  EXPECT_DOUBLE_EQ(d[0][2], 1.0);
}

}  // namespace
}  // namespace hoilcd
