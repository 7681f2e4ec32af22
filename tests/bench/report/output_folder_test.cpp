#include "hoilcd/bench/report/output_folder.h"

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/file_io.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

const OutputMarker kMarker = {"out.json", {"hoilcd_version", "methods"}, "thing"};

// The InputError message CheckOutputFolder throws for dir ("" when it throws none).
std::string Refusal(const std::string& dir) {
  try {
    CheckOutputFolder(dir, kMarker);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(OutputFolder, ANewAnEmptyAndAnEarlierOutputsFolderAreWrittenInto) {
  const test::TestDir temp;
  EXPECT_EQ(Refusal(temp / "new"), "");
  std::filesystem::create_directories(temp / "empty");
  EXPECT_EQ(Refusal(temp / "empty"), "");
  WriteFileAtomic(temp / "earlier/out.json", R"({"hoilcd_version": "0.1.0", "methods": {}, "more": 1})");
  WriteFileAtomic(temp / "earlier/notes.txt", "beside an earlier output, as the bench has always allowed");
  EXPECT_EQ(Refusal(temp / "earlier"), "");
}

TEST(OutputFolder, AFolderWithoutTheMarkerIsRefusedNamingWhatItHolds) {
  const test::TestDir temp;
  WriteFileAtomic(temp / "mine/notes.txt", "mine");
  WriteFileAtomic(temp / "mine/data/a.csv", "mine");
  EXPECT_EQ(Refusal(temp / "mine"), temp / "mine" +
                                        ": exists, is not empty (it holds data/ and notes.txt) and holds no earlier "
                                        "hoilcd thing (out.json); refusing to overwrite files in it: choose a new "
                                        "or empty folder");
}

TEST(OutputFolder, AMarkerThatIsNotJsonOrLacksAKeyIsNotAnEarlierOutput) {
  const test::TestDir temp;
  WriteFileAtomic(temp / "broken/out.json", "{not json");
  EXPECT_NE(Refusal(temp / "broken").find("(it holds out.json) and holds no earlier hoilcd thing"), std::string::npos);
  WriteFileAtomic(temp / "other/out.json", R"({"hoilcd_version": "0.1.0"})");
  EXPECT_NE(Refusal(temp / "other").find("holds no earlier hoilcd thing"), std::string::npos);
}

TEST(OutputFolder, AFileIsRefusedAndAFolderThatCannotBeMadeNamesItself) {
  const test::TestDir temp;
  WriteFileAtomic(temp / "file", "x");
  EXPECT_EQ(Refusal(temp / "file"), temp / "file" +
                                        ": is a file: expected a folder (new, empty, or holding an "
                                        "earlier hoilcd thing)");
  try {
    CreateOutputFolder(temp / "file/sub");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(temp / "file/sub" + ": cannot create the folder (", 0), 0u) << e.what();
  }
  CreateOutputFolder(temp / "a/b");
  EXPECT_TRUE(std::filesystem::is_directory(temp / "a/b"));
}

}  // namespace
}  // namespace hoilcd
