// The scene's camera.video object becomes VideoOptions; errors name the JSON path.
#include "hoilcd/sim/scene/scene_options.h"

#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace hoilcd {
namespace {

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

Scene PaperRoom(const std::vector<std::string>& overrides) {
  return LoadScene(std::string(HOILCD_TEST_SOURCE_DIR) + "/scenes/paper_room.json", overrides);
}

TEST(VideoOptions, SceneErrorsNameTheJsonPath) {
  EXPECT_EQ(VideoOptionsFromScene(PaperRoom({})).crf, 23);
  EXPECT_TRUE(VideoOptionsFromScene(PaperRoom({"camera.video.enabled=true"})).enabled);
  EXPECT_NE(ErrorOf([] { PaperRoom({"camera.video.crf=60"}); }).find("/camera/video/crf"), std::string::npos);
  EXPECT_NE(ErrorOf([] { PaperRoom({"camera.video.bitrate_kbps=-1"}); }).find("/camera/video/bitrate_kbps"),
            std::string::npos);
  EXPECT_NE(ErrorOf([] { PaperRoom({"camera.video.preset=\"warp\""}); }).find("/camera/video/preset"),
            std::string::npos);
  EXPECT_NE(ErrorOf([] { PaperRoom({"camera.video.colour=1"}); }).find("/camera/video"), std::string::npos);
  const std::string rate = ErrorOf([] { VideoOptionsFromScene(PaperRoom({"frame_rate_hz=25.123456"})); });
  EXPECT_NE(rate.find(": /frame_rate_hz: thermal.mp4 needs a frame rate"), std::string::npos) << rate;
  const std::string size = ErrorOf([] { VideoOptionsFromScene(PaperRoom({"camera.width_px=255"})); });
  EXPECT_NE(size.find(": /camera: thermal.mp4 (H.264, 4:2:0) needs an even width"), std::string::npos) << size;
}

}  // namespace
}  // namespace hoilcd
