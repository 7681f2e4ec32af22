// What the methods' front ends read of one frame, as the camera delivered it. In video mode
// (camera.video.enabled) the camera's only output is its H.264 recording, as the paper's was
// (section 5.1): SLCD's corners, the thumbnails and DLCD's person detector all read the decoded
// 8-bit frames (the dataset's thermal PNGs), and the detector maps them back to degC through the
// manifest's 8-bit window (20-30 degC by default, where people saturate, as in the paper). With
// video mode off the camera is radiometric: the detector also reads the uncompressed apparent
// temperatures, so it can tell skin (above the window) from clothing. The oracle front ends read
// the ground truth instead: the frame's EXR (true temperature, class channel) and persons.json.
#pragma once

#include <vector>

#include <opencv2/core/mat.hpp>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/tracking/byte_tracker.h"

namespace hoilcd {

struct FrontEndInput {
  cv::Mat thermal_u8;     // CV_8U: what every method reads (decoded video frames in video mode)
  cv::Mat radiometric_c;  // CV_32F degC for the person detector; empty in video mode
};

// camera.video.enabled in the dataset's scene.json (false when absent or unreadable).
bool IsVideoMode(const Dataset& dataset);

// Frame `frame` as the front ends read it, given IsVideoMode(dataset); the radiometric image is
// read only when the person detector runs (`detector`) and video mode is off.
FrontEndInput ReadFrontEndInput(const Dataset& dataset, int frame, bool video_mode, bool detector);

// What the oracle front ends read of one frame, from its EXR (read once for both).
struct GroundTruthInput {
  cv::Mat ideal_u8;     // CV_8U: T_true (before the sensor model) through the manifest's 8-bit window
  cv::Mat person_mask;  // CV_8U: 255 where the class channel is the manifest's "person"
};

// Frame `frame`'s ground truth: the ideal image when `ideal`, the person mask when `persons`.
// InputError naming the dataset when it has no EXRs or its manifest no "person" class.
GroundTruthInput ReadGroundTruthInput(const Dataset& dataset, int frame, bool ideal, bool persons);

// The people of one frame of persons.json as the tracker's output would give them: each visible
// person (visible fraction > 0) as a track with its id and visible-pixel box, in file order.
std::vector<Track> GroundTruthTracks(const FramePersons& frame);

}  // namespace hoilcd
