#include "hoilcd/sim/assets/data_dir.h"

#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <stdlib.h>

#include "hoilcd/core/util/error.h"
#include "hoilcd/sim/assets/asset.h"
#include "test_dir.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

TEST(DataDir, WithoutTheVariableTheBuildTreesShareFolderHoldsTheScenesAndAssets) {
  unsetenv(kDataDirVariable);
  const fs::path dir = DataDir();
  EXPECT_EQ(dir.filename(), "hoilcd");
  EXPECT_EQ(dir.parent_path().filename(), "share");
  EXPECT_TRUE(fs::is_regular_file(dir / "scenes" / "paper_room.json"));
  EXPECT_TRUE(fs::is_regular_file(dir / "assets" / "chair.gltf"));
  EXPECT_EQ(ShippedAssetDir(), (dir / "assets").string());
}

TEST(DataDir, BinaryPathIsThisTestProgram) { EXPECT_EQ(fs::path(BinaryPath()), fs::canonical("/proc/self/exe")); }

TEST(DataDir, AProgramWhoseFileWasReplacedWhileItRunsIsStillFoundWhereItWas) {
  // A rebuild during a long suite replaced the binary: every later run failed to find share/hoilcd.
  EXPECT_EQ(ProgramPathFromLink("/opt/hoilcd/bin/hoilcd (deleted)"), "/opt/hoilcd/bin/hoilcd");
  EXPECT_EQ(ProgramPathFromLink("/opt/hoilcd/bin/hoilcd"), "/opt/hoilcd/bin/hoilcd");
  EXPECT_EQ(ProgramPathFromLink(" (deleted)"), " (deleted)");
}

TEST(DataDir, TheVariableOverridesTheSearch) {
  test::TestDir dir;
  setenv(kDataDirVariable, dir.str().c_str(), 1);
  EXPECT_EQ(DataDir(), dir.str());
  EXPECT_EQ(ShippedAssetDir(), dir / "assets");
  unsetenv(kDataDirVariable);
}

TEST(DataDir, AVariableNamingNoFolderIsAnInputErrorNamingIt) {
  test::TestDir dir;
  const std::string missing = dir / "no_such_folder";
  setenv(kDataDirVariable, missing.c_str(), 1);
  try {
    DataDir();
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("HOILCD_DATA_DIR: '" + missing + "' is not a folder"), std::string::npos)
        << e.what();
  }
  unsetenv(kDataDirVariable);
}

}  // namespace
}  // namespace hoilcd
