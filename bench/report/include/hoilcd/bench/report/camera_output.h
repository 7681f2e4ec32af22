// What the camera's own output did to a dataset, measured from the folder alone: the video
// (thermal.mp4) against the uncompressed 8-bit frames (PSNR), the lens shading present in the
// apparent temperatures, and the frames frozen by flat-field corrections: the camera_output
// section of `hoilcd inspect` (and so of every bench report).
#pragma once

#include <string>

#include "hoilcd/bench/report/inspect.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/option_table.h"

namespace hoilcd {

// Defaults and ranges: Table() in camera_output.cpp.
struct CameraOutputOptions {
  int max_frames_compared;  // frames decoded and compared at most (evenly spaced), frames
  int patch_px;             // side of the corner and centre patches for shading, px
  int threads;              // decoding and comparing threads (0: every core)

  CameraOutputOptions();  // the registered defaults
  // Every field once: name, default, unit, range, description.
  static const OptionTable<CameraOutputOptions>& Table();
  // "" when valid, else the first problem ("field: must be ...").
  std::string Check() const;
};

struct CameraOutputStats {
  bool video_mode = false;        // camera.video.enabled in the dataset's scene.json
  std::string video_problem;      // "" when thermal.mp4 decoded to one frame per frame
  int video_frames = 0;           // frames decoded from thermal.mp4
  int frames_compared = 0;        // frames read (evenly spaced) for PSNR and shading
  int frames_shading = 0;         // of which not frozen, used for shading
  double psnr_mean_db = 0;        // decoded video vs uncompressed 8-bit frames, dB (100: identical)
  double psnr_min_db = 0;         // worst compared frame, dB
  bool thermal_is_video = false;  // the thermal PNGs (what methods read) are the decoded frames
  double shading_mean_k = 0;      // corner minus centre of T − T_true, mean over frames_shading, K
  double shading_p90_k = 0;       // its 90th percentile over compared frames, K
  int freeze_events = 0;          // frames listed as "freeze" in events.json
  int frozen_frames = 0;          // frames whose radiometric PNG has the previous frame's checksum
};

// Reads thermal.mp4, a subset of the EXRs and PNGs, scene.json and the manifest. A missing or
// undecodable thermal.mp4 is reported in video_problem, and frames without an EXR are skipped,
// not thrown.
CameraOutputStats MeasureCameraOutput(const Dataset& dataset, const CameraOutputOptions& options = {});

// The inspect section "camera_output" (booleans as 0/1).
InspectSection CameraOutputSection(const CameraOutputStats& stats);

}  // namespace hoilcd
