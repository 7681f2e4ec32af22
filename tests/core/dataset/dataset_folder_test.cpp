#include "hoilcd/core/dataset/dataset_folder.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <unistd.h>

#include "processes.h"
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
  for (const char* own : {"manifest.json", "scene.json", "poses.csv", "poses_tum.txt", "persons.json", "events.json",
                          "footprints.json", "thermal/000000.png", "radiometric/001995.png", "exr/1234567.exr"}) {
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
  const std::string dead = std::to_string(test::DeadPid());
  for (const std::string& f :
       {"manifest.json.tmp." + dead, "thermal/000001.png.tmp." + dead, std::string("notes.tmp.txt"),
        std::string("data/x.tmp.5"), std::string("thermal/000001.png")}) {
    Touch(dir, f);
  }
  RemoveDatasetTempFiles(dir.str());
  EXPECT_FALSE(fs::exists(dir / ("manifest.json.tmp." + dead)));
  EXPECT_FALSE(fs::exists(dir / ("thermal/000001.png.tmp." + dead)));
  EXPECT_TRUE(fs::exists(dir / "notes.tmp.txt"));
  EXPECT_TRUE(fs::exists(dir / "data/x.tmp.5"));
  EXPECT_TRUE(fs::exists(dir / "thermal/000001.png"));
}

// Issue 45, defect 4: a second render of the folder deleted the first one's temp files, whose
// rename then failed. Only those of processes that have ended (or this one's own) are removed.
TEST(DatasetFolder, RemovingTempFilesSparesThoseOfAProcessThatStillRuns) {
  test::TestDir dir;
  const test::LiveProcess writer;
  const std::string live = "thermal/000001.png.tmp." + std::to_string(writer.pid());
  const std::string dead = "thermal/000002.png.tmp." + std::to_string(test::DeadPid());
  const std::string own = "manifest.json.tmp." + std::to_string(::getpid());
  for (const std::string& f : {live, dead, own}) Touch(dir, f);
  RemoveDatasetTempFiles(dir.str());
  EXPECT_TRUE(fs::exists(dir / live));
  EXPECT_FALSE(fs::exists(dir / dead));
  EXPECT_FALSE(fs::exists(dir / own));
}

// The folder's lock file (hoilcd.lock, core/util/folder_lock.h) is hoilcd's: never named as the
// user's, and never deleted by a clean-up (only its holder deletes it).
TEST(DatasetFolder, TheFolderLockFileIsNeitherTheUsersNorCleanedUp) {
  test::TestDir dir;
  for (const char* f : {"hoilcd.lock", "manifest.json", "thermal/000000.png"}) Touch(dir, f);
  EXPECT_TRUE(ForeignFiles(dir.str()).empty());
  EXPECT_EQ(NonTempFiles(dir.str()), (std::vector<std::string>{"manifest.json", "thermal/000000.png"}));
  EXPECT_TRUE(RemoveDatasetFiles(dir.str()).empty());
  EXPECT_TRUE(fs::exists(dir / "hoilcd.lock"));
}

TEST(DatasetFolder, RemovingADatasetLeavesAndNamesWhatTheUserPutBesideIt) {
  test::TestDir dir;
  for (const char* f : {"manifest.json", "scene.json", "thermal/000000.png", "exr/000000.exr", "poses.csv.tmp.9",
                        "README.txt", "thermal/my_note.txt"}) {
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
