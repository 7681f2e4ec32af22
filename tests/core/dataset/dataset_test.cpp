#include "hoilcd/core/dataset/dataset.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "cpu_seconds.h"
#include "hoilcd/core/dataset/runs.h"
#include "hoilcd/core/util/error.h"
#include "input_error_of.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

using test::InputErrorOf;

std::vector<PoseRecord> SamplePoses(int count) {
  std::vector<PoseRecord> poses;
  for (int i = 0; i < count; ++i) {
    PoseRecord p;
    p.frame = i;
    p.time_s = i / 25.0;
    p.x_m = 0.1 * i + 1.0 / 3.0;
    p.y_m = -1e-300 * i;
    p.theta_rad = -0.7 * i;
    p.cam_x_m = p.x_m + 0.25;
    p.cam_y_m = p.y_m;
    p.cam_z_m = 0.8;
    p.cam_yaw_rad = p.theta_rad;
    p.cam_pitch_rad = 0.05;
    p.cam_roll_rad = -0.01 * i;
    p.odo_x_m = p.x_m + 1e-3 * i;
    p.odo_y_m = p.y_m - 2e-3 * i;
    p.odo_theta_rad = p.theta_rad + 1e-4;
    poses.push_back(p);
  }
  return poses;
}

std::vector<FramePersons> SamplePersons() {
  PersonRecord a{7,
                 cv::Rect2f(1.5f, 2.f, 3.25f, 4.f),
                 0.8,
                 0.2,
                 true,
                 "seated",
                 {{"seat", 2.5, 5.75, true}, {"left_hand", 1.0, 3.0, false}},
                 {}};
  PersonRecord b{9, cv::Rect2f(0.f, 0.f, 2.f, 2.f), 0.1, 0.9, false, "standing", {}, {}};
  return {{0, {a}}, {1, {}}, {2, {a, b}}};
}

std::vector<DatasetEvent> SampleEvents() {
  return {
      {0, "ffc", -1, "", "shutter"}, {1, "arrive", 9, "table2_seat1", ""}, {2, "swap", 7, "table1_seat0", "with 9"}};
}

// Writes a complete tiny dataset (8 x 6 px frames) with the library's own writer functions.
DatasetManifest WriteTinyDataset(const std::string& dir, int frames, bool complete) {
  DatasetManifest m;
  m.hoilcd_version = "test";
  m.scene_hash = ChecksumOf("{}");
  m.seed = 5;
  m.intrinsics = CameraIntrinsics::FromHorizontalFov(8, 6, 50);
  m.frame_count = frames;
  m.classes = {{"person", 1}, {"table", 2}};
  WriteDatasetFile(dir, "scene.json", "{}\n", &m);
  const int written = complete ? frames : frames - 1;
  for (int f = 0; f < written; ++f) {
    const cv::Mat thermal(6, 8, CV_8UC1, cv::Scalar(10 * f + 1));
    const cv::Mat radiometric(6, 8, CV_16UC1, cv::Scalar(29815 + 100 * f));
    WriteDatasetFile(dir, "thermal/" + FrameFileName(f, "png"), EncodePng(thermal), &m);
    WriteDatasetFile(dir, "radiometric/" + FrameFileName(f, "png"), EncodePng(radiometric), &m);
  }
  if (complete) {
    WriteDatasetFile(dir, "poses.csv", PosesToCsv(SamplePoses(frames)), &m);
    WriteDatasetFile(dir, "persons.json", PersonsToJson(SamplePersons()), &m);
    WriteDatasetFile(dir, "events.json", EventsToJson(SampleEvents()), &m);
  }
  m.complete = complete;
  WriteFileAtomic(dir + "/manifest.json", m.ToJson());
  return m;
}

TEST(FrameFileName, ZeroPadsToSixDigitsWithOrWithoutDot) {
  EXPECT_EQ(FrameFileName(123, "png"), "000123.png");
  EXPECT_EQ(FrameFileName(0, ".exr"), "000000.exr");
}

TEST(DatasetManifest, JsonRoundTripKeepsEveryField) {
  DatasetManifest m;
  m.hoilcd_version = "0.1.0";
  m.scene_hash = ChecksumOf("scene");
  m.seed = 18446744073709551615ull;
  m.intrinsics = CameraIntrinsics::FromHorizontalFov(256, 192, 50);
  m.frame_rate_hz = 25;
  m.frame_count = 1996;
  m.window_min_c = 20.5;
  m.window_max_c = 30.25;
  m.classes = {{"person", 1}, {"table", 2}, {"wall", 4}};
  m.files = {{"thermal/000000.png", ChecksumOf("a")}, {"poses.csv", ChecksumOf("b")}};
  m.complete = true;
  const DatasetManifest back = DatasetManifest::FromJson(m.ToJson(), "manifest.json");
  EXPECT_EQ(back.ToJson(), m.ToJson());
  EXPECT_EQ(back.seed, m.seed);
  EXPECT_EQ(back.intrinsics.fx, m.intrinsics.fx);
  EXPECT_EQ(back.classes, m.classes);
  EXPECT_EQ(back.files, m.files);
  EXPECT_TRUE(back.complete);
  EXPECT_EQ(back.FramesWritten(), 1);
}

TEST(DatasetManifest, OutputsRoundTripAreAllWhenAbsentAndBadOnesAreReportedAtTheirPointer) {
  DatasetManifest m;
  ASSERT_TRUE(DatasetOutputs::Parse("persons,thermal", &m.outputs).empty());
  const DatasetManifest back = DatasetManifest::FromJson(m.ToJson(), "manifest.json");
  EXPECT_EQ(back.outputs.ToText(), "thermal,persons");
  EXPECT_FALSE(back.outputs.exr);
  nlohmann::json j = nlohmann::json::parse(m.ToJson());
  // The manifest as `j` with a valid checksum of its own.
  const auto text = [&j] {
    nlohmann::json unsigned_part = j;
    unsigned_part.erase("manifest_checksum");
    nlohmann::json signed_part = unsigned_part;
    signed_part["manifest_checksum"] = ChecksumOf(unsigned_part.dump(2));
    return signed_part.dump(2);
  };
  j.erase("outputs");
  EXPECT_EQ(DatasetManifest::FromJson(text(), "m.json").outputs.ToText(), "thermal,radiometric,exr,video,persons");
  j["outputs"] = {"thermal", "depth"};
  EXPECT_NE(InputErrorOf([&] {
              DatasetManifest::FromJson(text(), "m.json");
            }).find("m.json: /outputs: unknown output 'depth'"),
            std::string::npos);
  j["outputs"] = "thermal";
  EXPECT_NE(InputErrorOf([&] { DatasetManifest::FromJson(text(), "m.json"); }).find("/outputs: expected an array"),
            std::string::npos);
  j["outputs"] = nlohmann::json::array();
  EXPECT_NE(InputErrorOf([&] { DatasetManifest::FromJson(text(), "m.json"); }).find("/outputs: expected at least one"),
            std::string::npos);
}

TEST(DatasetManifest, UnknownKeyWrongTypeAndEscapingPathAreReportedWithPointers) {
  DatasetManifest m;
  m.files = {{"../outside.png", ChecksumOf("x")}};
  std::string text = m.ToJson();
  text.replace(text.find("\"seed\": 0"), 9, "\"seed\": \"zero\", \"sead\": 1");
  const std::string message = InputErrorOf([&] { DatasetManifest::FromJson(text, "DIR/manifest.json"); });
  EXPECT_NE(message.find("DIR/manifest.json: /seed: expected a non-negative integer"), std::string::npos) << message;
  EXPECT_NE(message.find("DIR/manifest.json: /sead: unknown key"), std::string::npos) << message;
  EXPECT_NE(message.find("/files/../outside.png: expected a relative path"), std::string::npos) << message;
  EXPECT_NE(InputErrorOf([] { DatasetManifest::FromJson("{", "m.json"); }).find("invalid JSON"), std::string::npos);
}

TEST(Dataset, OpensATinyCompleteFolderAndReadsEverything) {
  test::TestDir dir;
  WriteTinyDataset(dir.str(), 3, true);
  const Dataset ds = Dataset::Open(dir.str());
  EXPECT_EQ(ds.num_frames(), 3);
  EXPECT_EQ(ds.manifest().classes.at("table"), 2);
  ASSERT_EQ(ds.poses().size(), 3u);
  EXPECT_EQ(ds.poses()[2].x_m, SamplePoses(3)[2].x_m);
  ASSERT_EQ(ds.persons().size(), 3u);
  EXPECT_EQ(ds.persons()[2].persons[1].id, 9);
  ASSERT_EQ(ds.events().size(), 3u);
  EXPECT_EQ(ds.events()[2].type, "swap");
  EXPECT_EQ(ds.scene_json(), "{}\n");
  const cv::Mat thermal = ds.Thermal(2);
  ASSERT_EQ(thermal.type(), CV_8UC1);
  EXPECT_EQ(thermal.size(), cv::Size(8, 6));
  EXPECT_EQ(thermal.at<uint8_t>(5, 7), 21);
  const cv::Mat celsius = ds.RadiometricC(1);
  ASSERT_EQ(celsius.type(), CV_32FC1);
  EXPECT_NEAR(celsius.at<float>(3, 4), 26.0, 1e-4);  // 29915 cK = 299.15 K
  EXPECT_THROW(ds.Thermal(3), std::logic_error);
}

// Damages a file the way a bad disk would: one bit of its middle byte flipped.
void FlipMiddleBit(const std::string& path) {
  std::string bytes = ReadFileBytes(path);
  bytes[bytes.size() / 2] ^= 0x01;
  WriteFileAtomic(path, bytes);
}

TEST(Dataset, CorruptedFrameIsAnErrorNamingThatFile) {
  test::TestDir dir;
  WriteTinyDataset(dir.str(), 3, true);
  const std::string frame = dir / "thermal/000001.png";
  FlipMiddleBit(frame);
  const std::string message = InputErrorOf([&] { Dataset::Open(dir.str()); });
  EXPECT_NE(message.find(frame + ": checksum mismatch"), std::string::npos) << message;
  EXPECT_EQ(message.find("000000.png"), std::string::npos) << message;
  EXPECT_NO_THROW(Dataset::Open(dir.str(), Verify::kNothing));
}

TEST(Dataset, VerifyOnReadChecksEachFileWhenItIsReadAndOnlyThen) {
  test::TestDir dir;
  WriteTinyDataset(dir.str(), 3, true);
  const std::string frame = dir / "thermal/000001.png";
  FlipMiddleBit(frame);
  const Dataset ds = Dataset::Open(dir.str(), Verify::kOnRead);  // the damaged frame is not read yet
  EXPECT_EQ(ds.Thermal(0).at<uint8_t>(0, 0), 1);
  EXPECT_EQ(ds.Thermal(2).at<uint8_t>(0, 0), 21);
  const std::string message = InputErrorOf([&] { ds.Thermal(1); });
  EXPECT_EQ(message.rfind(frame + ": checksum mismatch (manifest.json says ", 0), 0u) << message;
  EXPECT_NE(message.find("re-render the dataset"), std::string::npos) << message;
  // Unchecked reads see the damaged bytes (here the PNG decoder's own error, not a checksum).
  const std::string unchecked = InputErrorOf([&] { Dataset::Open(dir.str(), Verify::kNothing).Thermal(1); });
  EXPECT_NE(unchecked.find(frame + ": "), std::string::npos) << unchecked;
  EXPECT_EQ(unchecked.find("checksum"), std::string::npos) << unchecked;
}

TEST(Dataset, VerifyOnReadChecksTheSideFilesOpenReads) {
  test::TestDir dir;
  WriteTinyDataset(dir.str(), 3, true);
  std::string poses = ReadFileBytes(dir / "poses.csv");
  const size_t digit = poses.find_last_of("0123456789");
  poses[digit] = poses[digit] == '9' ? '8' : '9';  // still parses: only the checksum can tell
  WriteFileAtomic(dir / "poses.csv", poses);
  const std::string message = InputErrorOf([&] { Dataset::Open(dir.str(), Verify::kOnRead); });
  EXPECT_EQ(message.rfind(dir / "poses.csv" + ": checksum mismatch", 0), 0u) << message;
  EXPECT_NO_THROW(Dataset::Open(dir.str(), Verify::kNothing));
}

TEST(Dataset, VerifyOnReadRefusesAFileTheManifestDoesNotList) {
  test::TestDir dir;
  WriteTinyDataset(dir.str(), 3, true);
  WriteFileAtomic(dir / "extra.txt", "x");
  const Dataset checked = Dataset::Open(dir.str(), Verify::kOnRead);
  EXPECT_EQ(InputErrorOf([&] { checked.ReadFile("extra.txt"); }),
            dir / "extra.txt" + ": not listed in manifest.json, so its checksum cannot be checked");
  EXPECT_EQ(Dataset::Open(dir.str(), Verify::kNothing).ReadFile("extra.txt"), "x");
  EXPECT_EQ(checked.ReadFile("scene.json"), "{}\n");
}

TEST(Dataset, MissingListedFileIsAnErrorNamingThatFile) {
  test::TestDir dir;
  WriteTinyDataset(dir.str(), 3, true);
  fs::remove(dir / "radiometric/000002.png");
  const std::string message = InputErrorOf([&] { Dataset::Open(dir.str()); });
  EXPECT_NE(message.find(dir / "radiometric/000002.png" + ": listed in manifest.json but missing"), std::string::npos)
      << message;
}

TEST(Dataset, MissingManifestSaysItIsNotADatasetFolder) {
  test::TestDir dir;
  const std::string message = InputErrorOf([&] { Dataset::Open(dir.str()); });
  EXPECT_NE(message.find("manifest.json: no manifest.json: not a hoilcd dataset folder"), std::string::npos) << message;
}

TEST(Dataset, PartialDatasetSaysHowManyFramesAndToRerunRender) {
  test::TestDir dir;
  WriteTinyDataset(dir.str(), 3, false);
  const std::string message = InputErrorOf([&] { Dataset::Open(dir.str()); });
  EXPECT_EQ(message, dir.str() + ": dataset is partial: 2 of 3 frames; re-run hoilcd render to finish it");
}

TEST(PosesCsv, RoundTripIsExact) {
  const std::vector<PoseRecord> poses = SamplePoses(5);
  const std::string csv = PosesToCsv(poses);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "frame,t,x,y,theta,cam_x,cam_y,cam_z,cam_yaw,cam_pitch,cam_roll,odo_x,odo_y,odo_theta");
  const std::vector<PoseRecord> back = PosesFromCsv(csv, "poses.csv");
  ASSERT_EQ(back.size(), poses.size());
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(back[i].frame, poses[i].frame);
    EXPECT_EQ(back[i].time_s, poses[i].time_s);
    EXPECT_EQ(back[i].x_m, poses[i].x_m);
    EXPECT_EQ(back[i].y_m, poses[i].y_m);
    EXPECT_EQ(back[i].cam_pitch_rad, poses[i].cam_pitch_rad);
    EXPECT_EQ(back[i].cam_roll_rad, poses[i].cam_roll_rad);
    EXPECT_EQ(back[i].odo_theta_rad, poses[i].odo_theta_rad);
  }
  EXPECT_EQ(PosesToCsv(back), csv);
}

TEST(PosesCsv, MalformedLinesNameFileLineAndColumn) {
  std::string csv = PosesToCsv(SamplePoses(3));
  std::vector<std::string> lines;
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  lines[2].replace(lines[2].find(',', lines[2].find(',') + 1) + 1, 0, "x");  // line 3, column x
  lines[3] += ",7";                                                          // line 4: 15 columns
  std::string broken;
  for (const std::string& line : lines) broken += line + "\n";
  const std::string message = InputErrorOf([&] { PosesFromCsv(broken, "D/poses.csv"); });
  EXPECT_NE(message.find("D/poses.csv:3: column 3 'x': expected a finite number, got 'x"), std::string::npos)
      << message;
  EXPECT_NE(message.find("D/poses.csv:4: expected 14 columns, got 15"), std::string::npos) << message;
  const std::string header_message = InputErrorOf([] { PosesFromCsv("frame,t\n", "p.csv"); });
  EXPECT_NE(header_message.find("p.csv:1: expected header"), std::string::npos);
}

TEST(PosesTum, WritesWorldFromCamWithCameraLookingAlongHeading) {
  std::vector<PoseRecord> poses(1);
  poses[0].time_s = 1.5;
  poses[0].cam_x_m = 2;
  poses[0].cam_y_m = 1;
  poses[0].cam_z_m = 0.8;
  poses[0].cam_yaw_rad = M_PI / 2;
  const std::string tum = PosesToTum(poses);
  std::istringstream in(tum.substr(tum.find('\n') + 1));
  double t, tx, ty, tz, qx, qy, qz, qw;
  in >> t >> tx >> ty >> tz >> qx >> qy >> qz >> qw;
  ASSERT_FALSE(in.fail());
  EXPECT_EQ(t, 1.5);
  EXPECT_EQ(tx, 2);
  EXPECT_EQ(tz, 0.8);
  const Eigen::Vector3d forward = Eigen::Quaterniond(qw, qx, qy, qz) * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR((forward - Eigen::Vector3d::UnitY()).norm(), 0, 1e-12);  // yaw 90°: looks along +y
}

// Each row carries the full orientation: roll turns the image about the optical axis, so the
// camera's x axis (image right) leaves the horizontal plane by the roll angle.
TEST(PosesTum, CarriesEachRowsRollAboutTheOpticalAxis) {
  std::vector<PoseRecord> poses(2);
  poses[1].cam_roll_rad = 0.02;
  const std::string tum = PosesToTum(poses);
  std::istringstream in(tum.substr(tum.find('\n') + 1));
  std::vector<Eigen::Quaterniond> q;
  for (int row = 0; row < 2; ++row) {
    double t, tx, ty, tz, qx, qy, qz, qw;
    in >> t >> tx >> ty >> tz >> qx >> qy >> qz >> qw;
    ASSERT_FALSE(in.fail());
    q.emplace_back(qw, qx, qy, qz);
  }
  EXPECT_NEAR((q[0] * Eigen::Vector3d::UnitZ() - q[1] * Eigen::Vector3d::UnitZ()).norm(), 0, 1e-12);
  EXPECT_NEAR(std::abs((q[0] * Eigen::Vector3d::UnitX()).z()), 0, 1e-12);
  EXPECT_NEAR(std::abs((q[1] * Eigen::Vector3d::UnitX()).z()), std::sin(0.02), 1e-12);
}

TEST(PersonsJson, RoundTripKeepsEveryField) {
  const std::vector<FramePersons> persons = SamplePersons();
  const std::string text = PersonsToJson(persons);
  const std::vector<FramePersons> back = PersonsFromJson(text, "persons.json");
  ASSERT_EQ(back.size(), 3u);
  const PersonRecord& p = back[2].persons[0];
  EXPECT_EQ(p.id, 7);
  EXPECT_EQ(p.box_px, cv::Rect2f(1.5f, 2.f, 3.25f, 4.f));
  EXPECT_EQ(p.visible_fraction, 0.8);
  EXPECT_TRUE(p.seated);
  EXPECT_EQ(p.posture, "seated");
  ASSERT_EQ(p.contacts.size(), 2u);
  EXPECT_EQ(p.contacts[0].name, "seat");
  EXPECT_EQ(p.contacts[0].v_px, 5.75);
  EXPECT_FALSE(p.contacts[1].visible);
  EXPECT_EQ(PersonsToJson(back), text);
}

TEST(PersonsJson, WrittenFrameByFrameIsTheWholeDocumentsIndentedDump) {
  std::vector<FramePersons> persons;
  for (int f = 0; f < 50; ++f) {
    FramePersons frame = SamplePersons()[f % 3];
    frame.frame = f;
    for (PersonRecord& p : frame.persons) {
      p.posture = "line\nbreak \"quoted\" " + std::to_string(f);
      p.keypoints.push_back({"nose", {1.0 / 3, -2.5e-9, 7}, 12.25, -1, f % 2 == 0});
    }
    persons.push_back(frame);
  }
  const std::string text = PersonsToJson(persons, 1);
  EXPECT_EQ(text, nlohmann::json::parse(text).dump(1) + "\n");  // what one document dumps
  EXPECT_EQ(PersonsToJson(persons, 2), text);
  const nlohmann::json no_frames = {{"frames", nlohmann::json::array()}};
  EXPECT_EQ(PersonsToJson({}), no_frames.dump(1) + "\n");
  const std::string one_empty_frame = PersonsToJson({FramePersons{4, {}}});
  EXPECT_EQ(one_empty_frame, nlohmann::json::parse(one_empty_frame).dump(1) + "\n");
}

TEST(PersonsJson, FramesReadInParallelGiveTheWholeDocumentsResultAndItsErrors) {
  // Many frames, with strings holding quotes, brackets and commas, in two layouts.
  std::vector<FramePersons> persons;
  for (int f = 0; f < 300; ++f) {
    FramePersons frame = SamplePersons()[f % 3];
    frame.frame = f;
    for (PersonRecord& p : frame.persons) p.posture = "se\"a,t]{ed\\" + std::to_string(f);
    persons.push_back(frame);
  }
  const std::string text = PersonsToJson(persons);
  EXPECT_EQ(PersonsToJson(PersonsFromJson(text, "p.json")), text);
  const std::string compact = nlohmann::json::parse(text).dump();
  EXPECT_EQ(PersonsToJson(PersonsFromJson(compact, "p.json")), text);
  EXPECT_EQ(PersonsFromJson("{\"frames\": []}", "p.json").size(), 0u);

  // What is wrong in frame 150, or around the array, is named as when read whole.
  nlohmann::json bad = nlohmann::json::parse(text);
  bad["frames"][150]["persons"][0]["id"] = "seven";
  std::string message = InputErrorOf([&] { PersonsFromJson(bad.dump(1), "p.json"); });
  EXPECT_NE(message.find("p.json: /frames/150/persons/0/id"), std::string::npos) << message;
  bad = nlohmann::json::parse(text);
  bad["frames"][299]["extra"] = 1;
  message = InputErrorOf([&] { PersonsFromJson(bad.dump(), "p.json"); });
  EXPECT_NE(message.find("p.json: /frames/299/extra: unknown key"), std::string::npos) << message;
  bad = nlohmann::json::parse(text);
  bad["version"] = 2;
  message = InputErrorOf([&] { PersonsFromJson(bad.dump(), "p.json"); });
  EXPECT_NE(message.find("p.json: /version: unknown key"), std::string::npos) << message;
  const std::vector<std::string> broken_texts = {text + "]", text.substr(0, text.size() / 2), "{\"frames\": [1e400]}",
                                                 "{\"frames\": [{}, ]}", "{\"frames\": [\"]\"]}"};
  for (const std::string& broken : broken_texts) {
    message = InputErrorOf([&] { PersonsFromJson(broken, "p.json"); });
    EXPECT_NE(message.find("p.json"), std::string::npos) << message;
  }
}

TEST(PersonsJson, BadBoxIsReportedWithItsPointer) {
  const std::string message = InputErrorOf([] {
    PersonsFromJson(R"({"frames":[{"frame":0,"persons":[{"id":1,"box_px":[1,2,3],)"
                    R"("visible_fraction":1,"occlusion_fraction":0,"seated":true,)"
                    R"("posture":"seated","contacts":[]}]}]})",
                    "persons.json");
  });
  EXPECT_NE(message.find("persons.json: /frames/0/persons/0/box_px: expected [x, y, width, height]"), std::string::npos)
      << message;
}

TEST(EventsJson, RoundTripKeepsEveryFieldAndUnknownTypeIsAnError) {
  const std::vector<DatasetEvent> events = SampleEvents();
  const std::string text = EventsToJson(events);
  const std::vector<DatasetEvent> back = EventsFromJson(text, "events.json");
  ASSERT_EQ(back.size(), 3u);
  EXPECT_EQ(back[1].type, "arrive");
  EXPECT_EQ(back[1].person, 9);
  EXPECT_EQ(back[1].seat, "table2_seat1");
  EXPECT_EQ(back[2].detail, "with 9");
  EXPECT_EQ(EventsToJson(back), text);
  const std::string message = InputErrorOf([] {
    EventsFromJson(R"({"events":[{"frame":0,"type":"jump","person":1,"seat":"","detail":""}]})", "events.json");
  });
  EXPECT_NE(message.find("events.json: /events/0/type: expected one of arrive, leave, swap, ffc"), std::string::npos)
      << message;
}

std::vector<FootprintRecord> SampleFootprints() {
  FootprintRecord table;
  table.name = "table 0";
  table.centre_m = {1.25, 0.1 + 0.2};  // not exactly representable: must read back exactly
  table.half_size_m = {0.6, 0.4};
  table.yaw_deg = 90;
  FootprintRecord person;
  person.name = "standing person 4";
  person.kind = "circle";
  person.centre_m = {5.5, 2.75};
  person.radius_m = 0.3;
  return {table, person};
}

TEST(FootprintsJson, RoundTripKeepsEveryFieldExactly) {
  const std::string text = FootprintsToJson(SampleFootprints());
  const std::vector<FootprintRecord> back = FootprintsFromJson(text, "footprints.json");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].name, "table 0");
  EXPECT_EQ(back[0].kind, "rectangle");
  EXPECT_EQ(back[0].centre_m[1], 0.1 + 0.2);
  EXPECT_EQ(back[0].half_size_m[0], 0.6);
  EXPECT_EQ(back[0].yaw_deg, 90);
  EXPECT_EQ(back[1].kind, "circle");
  EXPECT_EQ(back[1].radius_m, 0.3);
  EXPECT_EQ(FootprintsToJson(back), text);
}

TEST(FootprintsJson, MalformedEntriesAreReportedWithFileAndPointer) {
  const std::string message = InputErrorOf([] {
    FootprintsFromJson(R"({"footprints":[
      {"name":"a","kind":"triangle","centre_m":[0,0],"half_size_m":[1,1],"yaw_deg":0,"radius_m":0},
      {"name":"b","kind":"circle","centre_m":[0],"half_size_m":[0,0],"yaw_deg":0,"radius_m":-1},
      {"name":"c","kind":"rectangle","half_size_m":[0,-2],"yaw_deg":"0","radius_m":0,"colour":1}]})",
                       "DIR/footprints.json");
  });
  for (const char* expected : {"DIR/footprints.json: /footprints/0/kind: expected rectangle or circle; got 'triangle'",
                               "DIR/footprints.json: /footprints/1/centre_m: expected an array of 2 numbers",
                               "DIR/footprints.json: /footprints/1/radius_m: expected a radius >= 0 m",
                               "DIR/footprints.json: /footprints/2/centre_m: missing",
                               "DIR/footprints.json: /footprints/2/half_size_m: expected sizes >= 0 m",
                               "DIR/footprints.json: /footprints/2/yaw_deg: expected a number",
                               "DIR/footprints.json: /footprints/2/colour: unknown key"}) {
    EXPECT_NE(message.find(expected), std::string::npos) << expected << "\n" << message;
  }
  const std::string missing = InputErrorOf([] { FootprintsFromJson("{}", "DIR/footprints.json"); });
  EXPECT_NE(missing.find("DIR/footprints.json: /footprints: missing"), std::string::npos) << missing;
}

TEST(Dataset, FolderWithoutFootprintsJsonReadsWithNoFootprints) {
  test::TestDir dir;
  WriteTinyDataset(dir.str(), 3, true);  // as written before footprints.json existed
  EXPECT_TRUE(Dataset::Open(dir.str()).footprints().empty());
}

TEST(Dataset, ListedFootprintsJsonIsReadAndAMalformedOneIsAnErrorNamingIt) {
  test::TestDir dir;
  DatasetManifest m = WriteTinyDataset(dir.str(), 3, true);
  WriteDatasetFile(dir.str(), "footprints.json", FootprintsToJson(SampleFootprints()), &m);
  WriteFileAtomic(dir / "manifest.json", m.ToJson());
  const Dataset ds = Dataset::Open(dir.str());
  ASSERT_EQ(ds.footprints().size(), 2u);
  EXPECT_EQ(ds.footprints()[1].name, "standing person 4");

  WriteDatasetFile(dir.str(), "footprints.json", R"({"footprints":[{"name":"x"}]})", &m);
  WriteFileAtomic(dir / "manifest.json", m.ToJson());
  const std::string message = InputErrorOf([&] { Dataset::Open(dir.str()); });
  EXPECT_NE(message.find(dir / "footprints.json" + ": /footprints/0/kind: missing"), std::string::npos) << message;
}

// Rewrites manifest.json through `edit`, then signs it again as hoilcd would (so that only the
// edited value, not the manifest checksum, is under test).
void EditManifest(const std::string& dir, const std::function<void(nlohmann::json&)>& edit) {
  nlohmann::json j = nlohmann::json::parse(ReadFileBytes(dir + "/manifest.json"));
  edit(j);
  j.erase("manifest_checksum");
  j["manifest_checksum"] = ChecksumOf(j.dump(2));
  WriteFileAtomic(dir + "/manifest.json", j.dump(2) + "\n");
}

TEST(Dataset, HugeFrameCountInTheManifestIsOneErrorNotAHang) {
  test::TestDir dir;
  WriteTinyDataset(dir.str(), 3, true);
  EditManifest(dir.str(), [](nlohmann::json& j) { j["frame_count"] = 2147483647; });
  const std::string message = InputErrorOf([&] { Dataset::Open(dir.str()); });
  EXPECT_NE(message.find("manifest.json: /frame_count: is 2147483647 but /files lists 3 thermal"), std::string::npos)
      << message.substr(0, 500);
}

TEST(Dataset, HandEditedManifestFailsItsChecksum) {
  test::TestDir dir;
  WriteTinyDataset(dir.str(), 3, true);
  std::string text = ReadFileBytes(dir / "manifest.json");
  text.replace(text.find("\"frame_count\": 3"), 16, "\"frame_count\": 2");
  WriteFileAtomic(dir / "manifest.json", text);
  const std::string message = InputErrorOf([&] { Dataset::Open(dir.str()); });
  EXPECT_NE(message.find("/manifest_checksum: does not match the manifest's content"), std::string::npos) << message;
}

TEST(Dataset, NumberTooLargeForADoubleIsAnInputErrorNamingTheFile) {
  const std::string manifest =
      InputErrorOf([] { DatasetManifest::FromJson("{\"seed\": 1e400}", "DIR/manifest.json"); });
  EXPECT_NE(manifest.find("DIR/manifest.json: invalid JSON"), std::string::npos) << manifest;
  const std::string persons = InputErrorOf([] { PersonsFromJson("{\"frames\": [1e400]}", "DIR/persons.json"); });
  EXPECT_NE(persons.find("DIR/persons.json: invalid JSON"), std::string::npos) << persons;
  const std::string events = InputErrorOf([] { EventsFromJson("[-1e400]", "DIR/events.json"); });
  EXPECT_NE(events.find("DIR/events.json: invalid JSON"), std::string::npos) << events;
}

TEST(Dataset, PngDeclaringAHugeImageIsRefusedBeforeDecoding) {
  test::TestDir dir;
  WriteTinyDataset(dir.str(), 3, true);
  // A PNG whose header claims 30000 x 30000 px (OpenCV would allocate 900 MB to decode it).
  std::string bytes = ReadFileBytes(dir / "thermal/000001.png");
  for (size_t at : {size_t{16}, size_t{20}}) {
    bytes.replace(at, 4, std::string("\x00\x00\x75\x30", 4));
  }
  WriteFileAtomic(dir / "thermal/000001.png", bytes);
  const Dataset ds = Dataset::Open(dir.str(), Verify::kNothing);
  const std::string message = InputErrorOf([&] { ds.Thermal(1); });
  EXPECT_NE(message.find("expected 8x6 px as in manifest.json, the PNG is 30000x30000"), std::string::npos) << message;
}

}  // namespace
}  // namespace hoilcd

namespace hoilcd {
namespace {

// Every JSON file of a dataset folder, read by its reader: nesting 10^5 deep and a repeated key
// are refused naming the file and pointer, and 10^5 list items are read or refused, each within
// two seconds (issue 45).
TEST(Dataset, EverySideFileRefusesDeepNestingAndRepeatedKeysAndReadsLongListsQuickly) {
  const std::vector<std::pair<std::string, std::function<void(const std::string&)>>> readers = {
      {"manifest.json", [](const std::string& t) { DatasetManifest::FromJson(t, "DIR/manifest.json"); }},
      {"persons.json", [](const std::string& t) { PersonsFromJson(t, "DIR/persons.json"); }},
      {"events.json", [](const std::string& t) { EventsFromJson(t, "DIR/events.json"); }},
      {"footprints.json", [](const std::string& t) { FootprintsFromJson(t, "DIR/footprints.json"); }},
      {"runs.json", [](const std::string& t) { RunsFromJson(t, "DIR/runs.json", 100000); }}};
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  std::string long_list = "[";
  for (int i = 0; i < 100000; ++i) long_list += std::string(i ? "," : "") + R"({"frame": 1})";
  long_list += "]";
  for (const auto& [file, read] : readers) {
    const auto error_within_two_seconds = [&, &read = read](const std::string& text) {
      const double start = test::ProcessCpuSeconds();  // CPU time: a loaded machine stretches wall time
      std::string error;
      try {
        read(text);
      } catch (const InputError& e) {
        error = e.what();
      }
      EXPECT_LT(test::ProcessCpuSeconds() - start, 2.0) << file;
      return error;
    };
    std::string error = error_within_two_seconds(R"({"frames": )" + deep + "}");
    EXPECT_NE(error.find("DIR/" + file + ": /frames/0/0/"), std::string::npos) << error.substr(0, 200);
    EXPECT_NE(error.find("nests deeper than 64 levels"), std::string::npos) << error.substr(0, 200);
    error = error_within_two_seconds(R"({"frames": [], "frames": []})");
    EXPECT_NE(error.find("DIR/" + file + ": /frames: the key \"frames\" is repeated"), std::string::npos) << error;
    error_within_two_seconds(long_list);
    error_within_two_seconds(R"({"frames": )" + long_list + ", \"runs\": " + long_list + ", \"events\": " + long_list +
                             "}");
  }
}

}  // namespace
}  // namespace hoilcd
