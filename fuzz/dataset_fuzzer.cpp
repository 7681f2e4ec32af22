// Fuzzes the dataset readers. The first byte picks the reader: 0 manifest.json, 1 poses.csv,
// 2 persons.json, 3 events.json, 4 an 8-bit frame PNG, 5 a 16-bit frame PNG, 6 a frame EXR,
// 7 footprints.json, 8 runs.json; the rest is the file. Only InputError may come out; anything else is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include <opencv2/core.hpp>

#include "fuzz_input.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  const hoilcd::CameraIntrinsics intrinsics = hoilcd::CameraIntrinsics::FromHorizontalFov(8, 6, 50);
  try {
    switch (data[0] % 9) {
      case 0:
        hoilcd::DatasetManifest::FromJson(text, "manifest.json");
        break;
      case 1:
        hoilcd::PosesFromCsv(text, "poses.csv");
        break;
      case 2:
        hoilcd::PersonsFromJson(text, "persons.json");
        break;
      case 3:
        hoilcd::EventsFromJson(text, "events.json");
        break;
      case 4:
        hoilcd::DecodeFramePng(text, "thermal.png", CV_8UC1, intrinsics);
        break;
      case 5:
        hoilcd::DecodeFramePng(text, "radiometric.png", CV_16UC1, intrinsics);
        break;
      case 7:
        hoilcd::FootprintsFromJson(text, "footprints.json");
        break;
      case 8:
        hoilcd::RunsFromJson(text, "runs.json", 9);
        break;
      default:  // the seed corpus frame is 16x12
        hoilcd::ReadExr(hoilcd::fuzz::WriteScratchFile("frame.exr", data + 1, size - 1), cv::Size(16, 12));
        break;
    }
  } catch (const hoilcd::InputError&) {
  }
  return 0;
}
