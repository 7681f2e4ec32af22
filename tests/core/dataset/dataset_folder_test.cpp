#include "hoilcd/core/dataset/dataset_folder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "test_dir.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

void Touch(const test::TestDir& dir, const std::string& relative) {
  const fs::path path = dir.path() / relative;
  fs::create_directories(path.parent_path());
  std::ofstream(path) << "x";
}

TEST(DatasetFolder, OwnNamesAreExactlyTheFilesHoilcdWrites) {
  for (const char* own : {"manifest.json", "scene.json", "poses.csv", "poses_tum.txt", "persons.json",
                          "events.json", "footprints.json", "thermal/000000.png", "radiometric/001995.png",
                          "exr/1234567.exr"}) {
    EXPECT_TRUE(IsDatasetFileName(own)) << own;
  }
  for (const char* other : {"notes.txt", "thermal/00001.png", "thermal/000001.exr", "exr/000001.png",
                            "thermal/abcdef.png", "sub/manifest.json", "report/report.md", ""}) {
    EXPECT_FALSE(IsDatasetFileName(other)) << other;
  }
  EXPECT_TRUE(IsDatasetTempFileName("manifest.json.tmp.4242"));
  EXPECT_TRUE(IsDatasetTempFileName("thermal/000003.png.tmp.1"));
  EXPECT_FALSE(IsDatasetTempFileName("notes.tmp.txt"));
  EXPECT_FALSE(IsDatasetTempFileName("my.tmp.1"));
  EXPECT_FALSE(IsDatasetTempFileName("manifest.json.tmp."));
  EXPECT_FALSE(IsDatasetTempFileName("manifest.json.tmp.12x"));
}

TEST(DatasetFolder, RemovingTempFilesKeepsUserFilesWithTmpInTheirName) {
  test::TestDir dir;
  for (const char* f : {"manifest.json.tmp.77", "thermal/000001.png.tmp.77", "notes.tmp.txt",
                        "data/x.tmp.5", "thermal/000001.png"}) {
    Touch(dir, f);
  }
  RemoveDatasetTempFiles(dir.str());
  EXPECT_FALSE(fs::exists(dir / "manifest.json.tmp.77"));
  EXPECT_FALSE(fs::exists(dir / "thermal/000001.png.tmp.77"));
  EXPECT_TRUE(fs::exists(dir / "notes.tmp.txt"));
  EXPECT_TRUE(fs::exists(dir / "data/x.tmp.5"));
  EXPECT_TRUE(fs::exists(dir / "thermal/000001.png"));
}

TEST(DatasetFolder, RemovingADatasetLeavesAndNamesWhatTheUserPutBesideIt) {
  test::TestDir dir;
  for (const char* f : {"manifest.json", "scene.json", "thermal/000000.png", "exr/000000.exr",
                        "poses.csv.tmp.9", "README.txt", "thermal/my_note.txt"}) {
    Touch(dir, f);
  }
  const std::vector<std::string> left = RemoveDatasetFiles(dir.str());
  EXPECT_EQ(left, (std::vector<std::string>{"README.txt", "thermal/my_note.txt"}));
  EXPECT_TRUE(fs::exists(dir / "README.txt"));
  EXPECT_FALSE(fs::exists(dir / "manifest.json"));
  EXPECT_FALSE(fs::exists(dir / "exr"));  // emptied frame folder removed
  EXPECT_TRUE(fs::exists(dir / "thermal/my_note.txt"));
}

TEST(DatasetFolder, ForeignFilesOfAMissingFolderAreNone) {
  test::TestDir dir;
  EXPECT_TRUE(ForeignFiles(dir / "absent").empty());
}

TEST(DatasetFolder, FileListIsShortenedForMessages) {
  EXPECT_EQ(JoinFileList({"a"}), "a");
  EXPECT_EQ(JoinFileList({"a", "b"}), "a and b");
  EXPECT_EQ(JoinFileList({"a", "b", "c", "d", "e"}), "a, b, c and 2 more");
}

}  // namespace
}  // namespace hoilcd
