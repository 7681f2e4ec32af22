// The dataset folder: the contract between the simulator (writer) and the benchmark (reader).
// manifest.json lists every file with its checksum; frames are PNGs; poses, persons and events
// are CSV/JSON side files. Writes are atomic, so a reader never accepts a half-written file.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

#include "hoilcd/core/dataset/runs.h"
#include "hoilcd/core/geometry/camera.h"
#include "hoilcd/core/util/file_io.h"  // the dataset's files are written and checked with it
#include "hoilcd/core/util/shard.h"

namespace hoilcd {

// A frame PNG's pixels (path names errors). The header must say k.width x k.height before
// anything is decoded (a small file can inflate to gigabytes), and the decoded type must be
// expected_type (CV_8UC1 thermal, CV_16UC1 radiometric); InputError otherwise.
cv::Mat DecodeFramePng(const std::string& bytes, const std::string& path, int expected_type, const CameraIntrinsics& k);

// "000123.png" for (123, "png"); a leading dot in the extension is accepted too.
std::string FrameFileName(int frame, const char* extension);

// Which outputs a dataset has (`hoilcd render --outputs`, the manifest's "outputs"); poses,
// events, footprints and scene.json are always written.
struct DatasetOutputs {
  bool thermal = true;      // thermal/NNNNNN.png
  bool radiometric = true;  // radiometric/NNNNNN.png
  bool exr = true;          // exr/NNNNNN.exr
  bool video = true;        // thermal.mp4
  bool persons = true;      // persons.json

  // The names, in the order "thermal", "radiometric", "exr", "video", "persons".
  static const std::vector<std::string>& AllNames();
  std::vector<std::string> Names() const;  // the enabled ones, in that order
  std::string ToText() const;              // Names() joined by commas
  bool Has(const std::string& name) const;
  // From a comma-separated list of names; "" when valid, else what is wrong (unknown or repeated
  // name, empty list).
  static std::string Parse(const std::string& text, DatasetOutputs* outputs);
  bool operator==(const DatasetOutputs& other) const { return Names() == other.Names(); }
  bool operator!=(const DatasetOutputs& other) const { return !(*this == other); }
};

// What a shard's folder (`hoilcd render --shard I/N`) holds of its sequence: frames [first_frame,
// end_frame) of the manifest's frame_count; `hoilcd merge` joins the N folders into the dataset.
struct DatasetShard {
  Shard shard;          // I/N
  int first_frame = 0;  // first frame of its range
  int end_frame = 0;    // one past its last frame
};

struct DatasetManifest {
  std::string hoilcd_version;                // version of the hoilcd that wrote the dataset
  std::string scene_hash;                    // ChecksumOf(resolved scene JSON)
  uint64_t seed = 0;                         // render seed
  CameraIntrinsics intrinsics;               // px
  double frame_rate_hz = 25;                 // Hz
  int frame_count = 0;                       // planned frames
  double window_min_c = 20;                  // °C, thermal PNG value 0
  double window_max_c = 30;                  // °C, thermal PNG value 255
  std::map<std::string, int> classes;        // class name -> id used in the EXR 'class' channel
  std::map<std::string, std::string> files;  // relative path -> checksum, every file written so far
  DatasetOutputs outputs;                    // which outputs were written (absent in older manifests: all)
  bool complete = false;                     // true once every frame and side file is written
  std::optional<DatasetShard> shard;         // set in a shard's folder only: not a dataset until merged

  std::string ToJson() const;
  // Every problem found (type errors, unknown keys) is reported with its JSON pointer.
  static DatasetManifest FromJson(const std::string& text, const std::string& path_for_errors);
  // Frames whose first per-frame output (thermal, radiometric or EXR, in that order) is listed
  // in `files`; frame_count when the dataset has no per-frame output.
  int FramesWritten() const;
  // The id of class `name` in the EXR 'class' channel, or kNoClass when the dataset has none.
  static constexpr int kNoClass = -2;  // matches no pixel (-1 is "nothing")
  int ClassId(const std::string& name) const;
};

// Writes DIR/relative_path atomically and records its checksum in manifest->files.
void WriteDatasetFile(const std::string& dir, const std::string& relative_path, std::string_view bytes,
                      DatasetManifest* manifest);

struct ContactRecord {
  std::string name;      // e.g. "left_hand", "seat"
  double u_px = 0;       // image column
  double v_px = 0;       // image row
  bool visible = false;  // not occluded and inside the image
};

// One of the 17 COCO keypoints of a person (COCO order and names).
struct KeypointRecord {
  std::string name;                 // "nose", "left_eye", ..., "right_ankle"
  std::array<double, 3> world_m{};  // world frame, m
  double u_px = -1;                 // image column (-1 when behind the camera)
  double v_px = -1;                 // image row
  bool visible = false;             // inside the image and not occluded (depth buffer)
};

struct PersonRecord {
  int id = -1;                    // person (instance) id, stable over the sequence
  cv::Rect2f box_px;              // visible-pixel bounding box
  double visible_fraction = 0;    // visible pixels / pixels the unoccluded person would cover
  double occlusion_fraction = 0;  // pixels hidden by other objects / unoccluded pixels
  bool seated = false;
  std::string posture;  // "seated", "standing", ...
  std::vector<ContactRecord> contacts;
  std::vector<KeypointRecord> keypoints;  // 17 COCO keypoints, or none (older datasets)
};

struct FramePersons {
  int frame = 0;
  std::vector<PersonRecord> persons;
};

struct DatasetEvent {
  int frame = 0;
  std::string type;  // "arrive" | "leave" | "swap" | "ffc" | "freeze" (a frame repeating an earlier one)
  int person = -1;   // -1 when no person is involved (ffc)
  std::string seat;
  std::string detail;
};

// The JSON text, frames formatted on `threads` threads (0: every core); the same at any count.
std::string PersonsToJson(const std::vector<FramePersons>& frames, int threads = 0);
// Frames are read on `threads` threads (0: every core); errors name "path: /json/pointer".
std::vector<FramePersons> PersonsFromJson(const std::string& text, const std::string& path, int threads = 0);
std::string EventsToJson(const std::vector<DatasetEvent>& events);
std::vector<DatasetEvent> EventsFromJson(const std::string& text, const std::string& path);

// A 2-D obstacle footprint on the floor (the World's obstacles, for drawing them without the
// scene): an oriented rectangle or a circle, world frame.
struct FootprintRecord {
  std::string name;                     // e.g. "table 0", "south wall", "standing person 3"
  std::string kind = "rectangle";       // "rectangle" | "circle"
  std::array<double, 2> centre_m{};     // m, world x, y of the centre
  std::array<double, 2> half_size_m{};  // m, rectangle half extents along its local x, y (0 for circles)
  double yaw_deg = 0;                   // deg, rectangle orientation (0 for circles)
  double radius_m = 0;                  // m, circle radius (0 for rectangles)
};

// footprints.json: {"footprints": [{"name", "kind", "centre_m", "half_size_m", "yaw_deg",
// "radius_m"}, ...]}; numbers read back exactly. Errors name the file and the JSON pointer.
std::string FootprintsToJson(const std::vector<FootprintRecord>& footprints);
std::vector<FootprintRecord> FootprintsFromJson(const std::string& text, const std::string& path);

// Ground truth and wheel odometry for one frame (a row of poses.csv).
struct PoseRecord {
  int frame = 0;
  double time_s = 0;
  double x_m = 0, y_m = 0, theta_rad = 0;              // robot base, ground truth
  double cam_x_m = 0, cam_y_m = 0, cam_z_m = 0;        // camera, ground truth
  double cam_yaw_rad = 0, cam_pitch_rad = 0;           // camera, ground truth (REP 103)
  double cam_roll_rad = 0;                             // camera roll about its optical axis
  double odo_x_m = 0, odo_y_m = 0, odo_theta_rad = 0;  // noisy wheel odometry
  int run = 0;  // recording run (runs.h): not a poses.csv column, set from runs.json by Dataset::Open

  CameraPose Camera() const;  // the cam_* fields (world_from_cam through CameraPose::WorldFromCam)
};

// poses.csv: a header line "frame,t,x,y,theta,cam_x,cam_y,cam_z,cam_yaw,cam_pitch,cam_roll,odo_x,
// odo_y,odo_theta" then one row per frame; numbers are written so that they read back exactly.
std::string PosesToCsv(const std::vector<PoseRecord>& poses);
// Errors name "path:line" and the column.
std::vector<PoseRecord> PosesFromCsv(const std::string& text, const std::string& path);
// TUM trajectory "t tx ty tz qx qy qz qw" of world_from_cam (OpenCV camera frame).
std::string PosesToTum(const std::vector<PoseRecord>& poses);

// How Dataset::Open checks the files against manifest.json's checksums (a mismatch or a missing
// file is an InputError naming it).
enum class Verify {
  kEveryFile,  // every listed file up front, in parallel, before anything is read
  kOnRead,     // each file when it is read through the Dataset: poses, persons, events, scene and
               // footprints in Open, a frame's PNG or EXR and thermal.mp4 when read (ReadFile).
               // Files nobody reads (a bench never reads most EXRs) are never read at all.
  kNothing,    // nothing: for readers that must see damaged bytes (decoder tests, fuzzing, inspect)
};

// A dataset folder opened for reading.
class Dataset {
 public:
  // Parses manifest.json; a partial dataset is an InputError ("dataset is partial: N of M
  // frames; re-run hoilcd render to finish it"). Checks files as `verify` says. Loads poses,
  // persons and events. A missing or damaged thermal.mp4 (a view of the frames, not their
  // source) is not an error but a line in warnings(). Checks and reads on `threads` threads
  // (0: every core).
  static Dataset Open(const std::string& dir, Verify verify = Verify::kEveryFile, int threads = 0);

  const DatasetManifest& manifest() const { return manifest_; }
  const std::string& dir() const { return dir_; }
  int num_frames() const { return manifest_.frame_count; }
  const std::vector<PoseRecord>& poses() const { return poses_; }
  // persons.json; InputError naming the missing output when it was not rendered.
  const std::vector<FramePersons>& persons() const;
  const std::vector<DatasetEvent>& events() const { return events_; }
  // The obstacle footprints from footprints.json; empty for datasets written before it existed.
  const std::vector<FootprintRecord>& footprints() const { return footprints_; }
  // The recording runs from runs.json; one run over every frame when the dataset has no runs.json.
  const std::vector<RunRecord>& runs() const { return runs_; }
  // Problems that do not stop reading (each "path: what"), for the caller to print.
  const std::vector<std::string>& warnings() const { return warnings_; }

  // InputError naming the missing output when the dataset was rendered without it.
  cv::Mat Thermal(int frame) const;                 // CV_8U from thermal/NNNNNN.png
  cv::Mat RadiometricC(int frame) const;            // CV_32F °C from radiometric/NNNNNN.png
  cv::Mat RadiometricCentikelvin(int frame) const;  // CV_16U as stored: K × 100
  // Throws InputError (the dataset folder: which output is missing and how to render it) unless
  // the dataset has `output` (a DatasetOutputs name); `needed_for` says what wanted it.
  void RequireOutput(const std::string& output, const std::string& needed_for) const;
  std::string scene_json() const;  // contents of scene.json
  // The bytes of DIR/name (a path relative to the dataset folder, e.g. "exr/000012.exr"); with
  // Verify::kOnRead checked against its manifest.json checksum (a file it does not list is an
  // InputError too).
  std::string ReadFile(const std::string& name) const;

 private:
  // Frame `frame` of the PNG output `output` ("thermal", "radiometric"), decoded as `type`;
  // `needed_for` goes to RequireOutput.
  cv::Mat FramePng(const std::string& output, int frame, int type, const std::string& needed_for) const;

  std::string dir_;
  Verify verify_ = Verify::kEveryFile;
  DatasetManifest manifest_;
  std::vector<PoseRecord> poses_;
  std::vector<FramePersons> persons_;
  std::vector<DatasetEvent> events_;
  std::vector<FootprintRecord> footprints_;
  std::vector<RunRecord> runs_;
  std::vector<std::string> warnings_;
};

}  // namespace hoilcd
