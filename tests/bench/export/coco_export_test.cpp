#include "hoilcd/bench/export/coco_export.h"

#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/scene/scene.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

TEST(CocoExport, EveryListedPersonBecomesAnAnnotationWithSeventeenFlaggedKeypoints) {
  const test::TestDir temp;
  const std::string dir = temp.str();
  SequenceOptions options;
  options.output_dir = dir + "/dataset";
  options.frames = 3;
  RenderSequence(LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json", {"crowd.walkers=1"}),
                 options);
  const std::string path = ExportCoco(dir + "/dataset", dir + "/coco");
  const nlohmann::json coco = nlohmann::json::parse(ReadFileBytes(path));
  const Dataset dataset = Dataset::Open(dir + "/dataset");
  size_t listed = 0;
  for (const FramePersons& f : dataset.persons()) listed += f.persons.size();
  ASSERT_GT(listed, 0u);
  EXPECT_EQ(coco["images"].size(), 3u);
  ASSERT_EQ(coco["annotations"].size(), listed);
  EXPECT_EQ(coco["categories"][0]["keypoints"].size(), 17u);
  EXPECT_EQ(coco["categories"][0]["keypoints"][0], "nose");
  int visible = 0;
  for (const auto& a : coco["annotations"]) {
    ASSERT_EQ(a["keypoints"].size(), 51u);
    int labelled = 0;
    for (int k = 0; k < 17; ++k) {
      const int flag = a["keypoints"][3 * k + 2];
      EXPECT_TRUE(flag == 0 || flag == 1 || flag == 2);
      labelled += flag > 0;
      visible += flag == 2;
    }
    EXPECT_EQ(a["num_keypoints"], labelled);
  }
  EXPECT_GT(visible, 0);
}

TEST(CocoExport, ADatasetWithoutKeypointsIsAnErrorNamingPersonsJsonAndTheFrame) {
  const test::TestDir temp;
  const std::string dir = temp / "dataset";
  SequenceOptions options;
  options.output_dir = dir;
  options.frames = 2;
  RenderSequence(LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json", {}), options);
  // As a dataset rendered before keypoints existed: persons without them, checksums consistent.
  std::vector<FramePersons> frames = Dataset::Open(dir).persons();
  ASSERT_FALSE(frames.empty());
  ASSERT_FALSE(frames[0].persons.empty());
  for (FramePersons& f : frames)
    for (PersonRecord& p : f.persons) p.keypoints.clear();
  DatasetManifest manifest = DatasetManifest::FromJson(ReadFileBytes(dir + "/manifest.json"), dir + "/manifest.json");
  WriteDatasetFile(dir, "persons.json", PersonsToJson(frames), &manifest);
  WriteFileAtomic(dir + "/manifest.json", manifest.ToJson());
  try {
    ExportCoco(dir, temp / "coco");
    FAIL() << "a dataset without keypoints was exported";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(dir + "/persons.json"), std::string::npos) << message;
    EXPECT_NE(message.find("frame 0, person " + std::to_string(frames[0].persons[0].id)), std::string::npos) << message;
    EXPECT_NE(message.find("expected the 17 COCO keypoints"), std::string::npos) << message;
  }
}

TEST(CocoExport, AMissingThermalImageIsAnErrorNamingItAndNothingIsWritten) {
  const test::TestDir temp;
  const std::string dir = temp.str();
  SequenceOptions options;
  options.output_dir = dir + "/dataset";
  options.frames = 3;
  RenderSequence(LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json"), options);
  std::filesystem::remove(dir + "/dataset/thermal/000001.png");
  try {
    ExportCoco(dir + "/dataset", dir + "/coco");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("thermal/000001.png"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/coco/person_keypoints.json"));
}

TEST(CocoExport, AFolderThatIsNotADatasetIsAnError) {
  const test::TestDir temp;
  const std::string dir = temp.str();
  EXPECT_THROW(ExportCoco(dir, dir + "/out"), InputError);
}

}  // namespace
}  // namespace hoilcd
