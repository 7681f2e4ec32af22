#include "hoilcd/bench/evaluation/tracking_metrics.h"

#include <gtest/gtest.h>

#include "option_properties.h"

namespace hoilcd {
namespace {

// Person `id` at a fixed box, 40 px apart from the next id.
PersonRecord Person(int id, double visible_fraction = 1.0) {
  PersonRecord p;
  p.id = id;
  p.box_px = cv::Rect2f(40.f * id, 10.f, 20.f, 30.f);
  p.visible_fraction = visible_fraction;
  return p;
}

TrackedBox Track(int track_id, int on_person) {
  return {track_id, cv::Rect2f(40.f * on_person + 1.f, 10.f, 20.f, 30.f), {}};
}

// Persons 1 and 2 in every frame of `frames`.
std::vector<FramePersons> TwoPersons(int frames) {
  std::vector<FramePersons> out;
  for (int f = 0; f < frames; ++f) out.push_back({f, {Person(1), Person(2)}});
  return out;
}

TEST(TrackingMetrics, PerfectTracksGiveMotaAndIdf1OfOne) {
  std::vector<FrameTracks> tracks;
  for (int f = 0; f < 10; ++f) tracks.push_back({f, {Track(10, 1), Track(20, 2)}});
  const TrackingMetrics m = ComputeTrackingMetrics(TwoPersons(10), tracks);
  EXPECT_EQ(m.gt_boxes, 20);
  EXPECT_EQ(m.true_positives, 20);
  EXPECT_EQ(m.id_switches, 0);
  EXPECT_EQ(m.mota, 1.0);
  EXPECT_EQ(m.idf1, 1.0);
  EXPECT_EQ(m.precision, 1.0);
  EXPECT_EQ(m.recall, 1.0);
}

TEST(TrackingMetrics, IdsSwappedInTheMiddleGiveTwoSwitchesAndHalfIdf1) {
  // Frames 0-4: track 10 on person 1, 20 on 2; frames 5-9 the other way round.
  // IDSW = 2 (both persons), MOTA = 1 - 2/20; best id assignment covers 5 + 5 of 20 frames per
  // side: IDF1 = 2 * 10 / (20 + 20).
  std::vector<FrameTracks> tracks;
  for (int f = 0; f < 10; ++f) {
    tracks.push_back({f, f < 5 ? std::vector<TrackedBox>{Track(10, 1), Track(20, 2)}
                               : std::vector<TrackedBox>{Track(10, 2), Track(20, 1)}});
  }
  const TrackingMetrics m = ComputeTrackingMetrics(TwoPersons(10), tracks);
  EXPECT_EQ(m.id_switches, 2);
  EXPECT_DOUBLE_EQ(m.mota, 0.9);
  EXPECT_EQ(m.idtp, 10);
  EXPECT_DOUBLE_EQ(m.idf1, 0.5);
}

TEST(TrackingMetrics, OneTrackReplacedByANewIdGivesOneSwitch) {
  // Person 1 tracked as 10 in frames 0-5, as 30 in 6-9: IDSW 1, MOTA 0.95,
  // IDTP = 6 (1 -> 10) + 10 (2 -> 20): IDF1 = 32 / 40.
  std::vector<FrameTracks> tracks;
  for (int f = 0; f < 10; ++f) tracks.push_back({f, {Track(f < 6 ? 10 : 30, 1), Track(20, 2)}});
  const TrackingMetrics m = ComputeTrackingMetrics(TwoPersons(10), tracks);
  EXPECT_EQ(m.id_switches, 1);
  EXPECT_DOUBLE_EQ(m.mota, 0.95);
  EXPECT_EQ(m.idtp, 16);
  EXPECT_DOUBLE_EQ(m.idf1, 0.8);
}

TEST(TrackingMetrics, MissesFalseAlarmsAndIgnoredPersonsAreCounted) {
  // Frame 0: person 1 tracked, person 2 missed, a false box far away. Frame 1: person 3 is barely
  // visible and ignored, so the track on it is neither a hit nor a false positive.
  std::vector<FramePersons> truth = {{0, {Person(1), Person(2)}}, {1, {Person(1), Person(3, 0.05)}}};
  std::vector<FrameTracks> tracks = {{0, {Track(10, 1), Track(99, 5)}}, {1, {Track(10, 1), Track(33, 3)}}};
  TrackingMetricsOptions options;
  options.min_visible_fraction = 0.1;
  const TrackingMetrics m = ComputeTrackingMetrics(truth, tracks, options);
  EXPECT_EQ(m.gt_boxes, 3);
  EXPECT_EQ(m.predicted_boxes, 3);
  EXPECT_EQ(m.true_positives, 2);
  EXPECT_EQ(m.false_negatives, 1);
  EXPECT_EQ(m.false_positives, 1);
  EXPECT_DOUBLE_EQ(m.precision, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(m.recall, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(m.mota, 1.0 - 2.0 / 3.0);
  const TrackingMetrics counted = ComputeTrackingMetrics(truth, tracks);
  EXPECT_EQ(counted.gt_boxes, 4);
  EXPECT_EQ(counted.true_positives, 3);
}

TEST(TrackingMetrics, PersonsWithALowVisibleBoxAreIgnoredWithTheirTracks) {
  // Person 1 is 30 px high, person 2 is cut to 12 px: at a 13 px minimum person 2 and the track
  // on it are ignored; at 12 px it counts.
  PersonRecord low = Person(2);
  low.box_px.height = 12;
  TrackedBox on_low = Track(20, 2);
  on_low.box.height = 12;
  const std::vector<FramePersons> truth = {{0, {Person(1), low}}};
  const std::vector<FrameTracks> tracks = {{0, {Track(10, 1), on_low, Track(99, 5)}}};
  TrackingMetricsOptions options;
  options.min_box_height_px = 13;
  const TrackingMetrics ignored = ComputeTrackingMetrics(truth, tracks, options);
  EXPECT_EQ(ignored.gt_boxes, 1);
  EXPECT_EQ(ignored.predicted_boxes, 2);
  EXPECT_EQ(ignored.true_positives, 1);
  EXPECT_EQ(ignored.false_positives, 1);
  options.min_box_height_px = 12;
  const TrackingMetrics counted = ComputeTrackingMetrics(truth, tracks, options);
  EXPECT_EQ(counted.gt_boxes, 2);
  EXPECT_EQ(counted.true_positives, 2);
}

TEST(TrackingMetrics, HoiErrorIsTheDistanceToTheNearestPointOfTheMatchedTrack) {
  PersonRecord p = Person(1);
  p.contacts = {{"seat", 45, 38, true}, {"hand", 50, 20, true}, {"foot", 0, 0, false}};
  TrackedBox t = Track(10, 1);
  t.hoi_points_px = {{46, 38}, {54, 20}, {200, 200}};  // errors 1 and 4; hidden contact skipped
  const TrackingMetrics m = ComputeTrackingMetrics({{0, {p}}, {1, {p}}}, {{0, {t}}, {1, {Track(10, 1)}}});
  EXPECT_EQ(m.hoi_contacts, 4);
  EXPECT_EQ(m.hoi_contacts_without_points, 2);  // frame 1: the track has no HOI points
  EXPECT_DOUBLE_EQ(m.hoi_median_error_px, 2.5);
  EXPECT_DOUBLE_EQ(m.hoi_fraction_within_tolerance, 0.25);
  EXPECT_EQ(m.ToJson()["hoi_median_error_px"], 2.5);
}

TEST(TrackingMetricsOptions, CheckNamesWhatIsWrong) {
  TrackingMetricsOptions options;
  EXPECT_EQ(options.Check(), "");
  options.iou_threshold = 0;
  EXPECT_NE(options.Check().find("iou_threshold"), std::string::npos);
  options = {};
  options.min_box_height_px = -1;
  EXPECT_NE(options.Check().find("min_box_height_px"), std::string::npos);
}

TEST(TrackingMetricsOptions, HoldTheirTablesDefaultsScoringEveryoneAndEveryBoundIsChecked) {
  EXPECT_EQ(TrackingMetricsOptions().min_visible_fraction, 0);
  EXPECT_EQ(TrackingMetricsOptions().min_box_height_px, 0);
  ExpectConstructedHoldsTheTableDefaults<TrackingMetricsOptions>();
  EXPECT_EQ(ExpectEveryBoundCrossedIsNamedByCheck<TrackingMetricsOptions>(), 6);
}

}  // namespace
}  // namespace hoilcd
