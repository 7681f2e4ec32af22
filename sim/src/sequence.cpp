#include "hoilcd/sim/sequence.h"

#include <chrono>
#include <future>
#include <memory>
#include <filesystem>
#include <optional>

#include "hoilcd/core/dataset.h"
#include "hoilcd/core/dataset_folder.h"
#include "hoilcd/core/parallel.h"
#include "hoilcd/core/progress.h"
#include "hoilcd/sim/exr_io.h"
#include "hoilcd/sim/renderer.h"
#include "hoilcd/sim/scene_options.h"
#include "hoilcd/sim/sensor.h"
#include "hoilcd/sim/video.h"
#include "hoilcd/sim/visibility.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

std::string FramePath(const char* folder, int frame, const char* extension) {
  return std::string(folder) + "/" + FrameFileName(frame, extension);
}

// A frame counts as done when all three of its files are listed and match their checksums.
bool FrameDone(const std::string& dir, const DatasetManifest& manifest, int frame) {
  for (const std::string& rel : {FramePath("thermal", frame, "png"), FramePath("radiometric", frame, "png"),
                                FramePath("exr", frame, "exr")}) {
    const auto it = manifest.files.find(rel);
    if (it == manifest.files.end()) return false;
    std::error_code ec;
    if (!fs::exists(dir + "/" + rel, ec)) return false;
    if (ChecksumOf(ReadFileBytes(dir + "/" + rel)) != it->second) return false;
  }
  return true;
}

// The uncompressed 8-bit frame, as the render wrote it, from the EXR's T channel (float32, so
// exactly the temperature the thermal PNG was made from).
cv::Mat UncompressedFrame(const std::string& dir, int frame, const SensorOptions& sensor_options, cv::Size size) {
  const std::string path = dir + "/" + FramePath("exr", frame, "exr");
  for (const auto& [name, channel] : ReadExr(path, size)) {
    if (name == "T") return ToDisplay8Bit(channel, sensor_options.display_min_c, sensor_options.display_max_c);
  }
  throw InputError(path, "no T channel");
}

cv::Mat ToFloat(const cv::Mat& m) {
  cv::Mat f;
  m.convertTo(f, CV_32F);
  return f;
}

}  // namespace

std::string SequenceOptions::Check() const {
  if (output_dir.empty()) return "an output folder is required";
  if (frames < 0) return "frames must be 0 (all) or positive";
  if (threads < 0) return "threads must be 0 (every core) or positive";
  if (checkpoint_every_frames < 1) return "checkpoint_every_frames must be positive";
  return "";
}

// Bump when a change alters rendered bytes (2: irregular chairs; 3: robot steers on odometry,
// camera vibration, cam_roll in poses.csv; 4: lens shading, FFC freeze; 5: articulated people;
// 6: the robot steers on localised odometry by default; 7: walkers planned in free space, clear of
// each other by distance, with cross and overtake bouts; 8: seated arms kept within their own
// half of the gap to each neighbour, gestures on the roomier side; 9: walkers enter and leave
// through the room's doors, seated people look at whichever neighbours sit at their table, chair
// jitter never squeezes neighbours together).
constexpr int kSimulatorRevision = 9;

std::string SimulatorVersion() { return std::string(HOILCD_VERSION) + "+sim" + std::to_string(kSimulatorRevision); }

SequenceResult RenderSequence(const Scene& scene, const SequenceOptions& options) {
  if (const std::string problem = options.Check(); !problem.empty()) throw InputError("render", problem);
  const auto start = std::chrono::steady_clock::now();
  const std::string& dir = options.output_dir;
  const int frames = options.frames > 0 ? std::min(options.frames, scene.frames) : scene.frames;

  const BandRadianceTable table;
  World world(scene, table);
  const CameraIntrinsics intrinsics = IntrinsicsFromScene(scene);
  const RobotRun run = SimulateSceneRobot(scene, world.obstacles());
  HOILCD_CHECK(static_cast<int>(run.samples.size()) >= frames);
  world.PlanCrowd(run.samples);
  const SensorOptions sensor_options = SensorOptionsFromScene(scene);
  const VideoOptions video_options = VideoOptionsFromScene(scene);
  auto new_sensor = [&] {
    return std::make_unique<SensorModel>(sensor_options, intrinsics.width, intrinsics.height,
                                         scene.frame_rate_hz, scene.seed, &table, options.threads);
  };
  std::unique_ptr<SensorModel> sensor = new_sensor();
  FrameRenderer renderer(world, intrinsics, RenderOptionsFromScene(scene, options.threads));

  // An existing folder must be an earlier run of this very scene; anything else is the user's.
  DatasetManifest manifest;
  const std::string manifest_path = dir + "/manifest.json";
  std::error_code ec;
  if (fs::exists(manifest_path, ec)) {
    DatasetManifest old = DatasetManifest::FromJson(ReadFileBytes(manifest_path), manifest_path);
    if (old.hoilcd_version != SimulatorVersion()) {
      throw InputError(dir, "holds a dataset rendered by hoilcd " + old.hoilcd_version + " (this is " +
                                SimulatorVersion() +
                                "), whose frames would not match new ones; delete it or choose another "
                                "output folder");
    }
    if (old.scene_hash != scene.hash || old.seed != scene.seed) {
      throw InputError(dir, "holds a dataset of another scene or seed (scene hash " + old.scene_hash +
                                ", seed " + std::to_string(old.seed) +
                                "); choose another output folder or delete this one");
    }
    manifest = old;
  } else if (const std::vector<std::string> foreign = ForeignFiles(dir); !foreign.empty()) {
    // Only temp files of a run killed before its first manifest may be there.
    throw InputError(dir, "exists, is not empty and is not a hoilcd dataset (it holds " + JoinFileList(foreign) +
                              "); refusing to write into it");
  }
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir, "cannot create the output folder (" + ec.message() + ")");
  // A killed run may leave temp files of atomic writes ("NAME.tmp.PID"); they were never
  // renamed into place, so nothing refers to them. Only those exact names are removed.
  RemoveDatasetTempFiles(dir);

  manifest.hoilcd_version = SimulatorVersion();
  manifest.scene_hash = scene.hash;
  manifest.seed = scene.seed;
  manifest.intrinsics = intrinsics;
  manifest.frame_rate_hz = scene.frame_rate_hz;
  manifest.frame_count = frames;
  manifest.window_min_c = sensor_options.display_min_c;
  manifest.window_max_c = sensor_options.display_max_c;
  manifest.classes = world.classes();
  manifest.complete = false;

  std::vector<bool> done(frames, false);
  bool any_done = false;
  for (int f = 0; f < frames; ++f) {
    done[f] = FrameDone(dir, manifest, f);
    any_done = any_done || done[f];
  }
  // Drop listings of files that are not (or no longer) valid frames or side files.
  for (auto it = manifest.files.begin(); it != manifest.files.end();) {
    bool keep = false;
    for (int f = 0; f < frames && !keep; ++f) {
      keep = done[f] && (it->first == FramePath("thermal", f, "png") ||
                         it->first == FramePath("radiometric", f, "png") ||
                         it->first == FramePath("exr", f, "exr"));
    }
    it = keep ? std::next(it) : manifest.files.erase(it);
  }
  WriteFileAtomic(manifest_path, manifest.ToJson());

  SequenceResult result;
  result.frames_total = frames;
  std::vector<FramePersons> persons(frames);
  ProgressReporter progress("render", frames, "frames");
  int sensor_frame = -1;  // last frame the sensor model has seen
  std::future<void> writing;  // the frame being encoded and written, if any
  auto finish_writing = [&writing] {
    if (writing.valid()) writing.get();  // rethrows a write error here
  };
  int since_checkpoint = 0;
  // thermal.mp4 is encoded from the uncompressed 8-bit frames in frame order: while they are
  // written when every frame is rendered by this call, else at the end from the EXRs on disk.
  // Both feed the encoder the same frames, so a resumed render gives the same file.
  double video_s = 0.0;
  std::unique_ptr<VideoEncoder> streaming_video;
  if (!any_done) {
    streaming_video = std::make_unique<VideoEncoder>(video_options, intrinsics.width, intrinsics.height,
                                                     scene.frame_rate_hz);
  }
  for (int f = 0; f < frames; ++f) {
    if (options.cancel && options.cancel->load()) {
      finish_writing();
      WriteFileAtomic(manifest_path, manifest.ToJson());
      throw RenderInterrupted("interrupted after " + std::to_string(f) + " frames; re-run the same command to resume");
    }
    const RobotSample& sample = run.samples[f];
    world.SetTime(sample.time_s);
    if (done[f]) {
      // Kept from an earlier run: ground truth comes from its stored instance ids.
      const ExrChannels exr = ReadExr(dir + "/" + FramePath("exr", f, "exr"), {intrinsics.width, intrinsics.height});
      cv::Mat ids, depth;
      for (const auto& [name, channel] : exr) {
        if (name == "id") channel.convertTo(ids, CV_32S);
        if (name == "Z") channel.convertTo(depth, CV_32F);
      }
      if (!ids.empty()) persons[f] = {f, VisiblePersons(world, intrinsics, sample.camera, ids, depth)};
      ++result.frames_reused;
      progress.Update();
      continue;
    }
    if (f > 0 && sensor_frame != f - 1) {
      // Resuming after kept frames: a fresh model replays the frames its state depends on (the
      // previous frame; during an FFC freeze, back to the frame it shows): the resume contract.
      sensor = new_sensor();
      for (int replay = sensor->ReplayFrom(f); replay < f; ++replay) {
        world.SetTime(run.samples[replay].time_s);
        sensor->Apply(replay, renderer.Render(run.samples[replay].camera).radiance);
      }
      world.SetTime(sample.time_s);
    }
    const FrameBuffers buffers = renderer.Render(sample.camera);
    const cv::Mat temperature = sensor->Apply(f, buffers.radiance);
    sensor_frame = f;
    const cv::Mat ideal = sensor->IdealTemperature(buffers.radiance);
    persons[f] = {f, VisiblePersons(world, intrinsics, sample.camera, buffers.instance, buffers.depth_m)};

    // Encoding and writing (two PNGs and an EXR, most of a frame's cost) overlap with rendering
    // the next frame. One frame at most is in flight and only its writer touches the manifest
    // meanwhile, so a checkpoint (taken after it finished) lists only complete files.
    finish_writing();
    if (since_checkpoint >= options.checkpoint_every_frames) {
      WriteFileAtomic(manifest_path, manifest.ToJson());
      since_checkpoint = 0;
    }
    writing = std::async(std::launch::async, [&, f, temperature, ideal, buffers] {
      const cv::Mat display =
          ToDisplay8Bit(temperature, sensor_options.display_min_c, sensor_options.display_max_c);
      WriteDatasetFile(dir, FramePath("thermal", f, "png"), EncodePng(display), &manifest);
      if (streaming_video) {
        const auto video_start = std::chrono::steady_clock::now();
        streaming_video->Add(display);
        video_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - video_start).count();
      }
      WriteDatasetFile(dir, FramePath("radiometric", f, "png"), EncodePng(ToCentikelvin16(temperature)),
                       &manifest);
      WriteDatasetFile(dir, FramePath("exr", f, "exr"),
                       EncodeExr({{"T", temperature},
                                  {"T_true", ideal},
                                  {"Z", buffers.depth_m},
                                  {"id", ToFloat(buffers.instance)},
                                  {"class", ToFloat(buffers.class_id)}}),
                       &manifest);
    });
    ++result.frames_rendered;
    ++since_checkpoint;
    progress.Update();
  }
  finish_writing();
  progress.Done();

  // The video; in video mode its decoded frames become the thermal PNGs that methods read.
  const auto video_start = std::chrono::steady_clock::now();
  std::string mp4;
  if (streaming_video && streaming_video->frames_added() == frames) {
    mp4 = streaming_video->Finish();
  } else {
    VideoEncoder encoder(video_options, intrinsics.width, intrinsics.height, scene.frame_rate_hz);
    for (int f = 0; f < frames; ++f) encoder.Add(UncompressedFrame(dir, f, sensor_options, {intrinsics.width, intrinsics.height}));
    mp4 = encoder.Finish();
  }
  WriteDatasetFile(dir, "thermal.mp4", mp4, &manifest);
  if (video_options.enabled) {
    const DecodedVideo video = DecodeVideo(mp4, dir + "/thermal.mp4");
    HOILCD_CHECK_MSG(static_cast<int>(video.frames.size()) == frames,
                     "decoded " << video.frames.size() << " of " << frames << " frames");
    // Written in parallel (each write waits for its fsync), listed in the manifest in order.
    std::vector<std::string> checksums(frames);
    ParallelFor(frames, ResolveThreadCount(options.threads), [&](int64_t f) {
      const std::string bytes = EncodePng(video.frames[f]);
      WriteFileAtomic(dir + "/" + FramePath("thermal", static_cast<int>(f), "png"), bytes);
      checksums[f] = ChecksumOf(bytes);
    });
    for (int f = 0; f < frames; ++f) manifest.files[FramePath("thermal", f, "png")] = checksums[f];
  }
  video_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - video_start).count();

  // Side files, then the manifest that declares the dataset complete.
  const std::vector<PoseRecord> poses = PoseRecordsOf(run, frames);
  std::vector<DatasetEvent> events;
  for (const DatasetEvent& e : world.events())
    if (e.frame < frames) events.push_back(e);
  for (int f : sensor->FfcFrames(frames)) {
    events.push_back({f, "ffc", -1, "", "flat-field correction (shutter)"});
    for (int frozen = f; frozen < frames && sensor->ShownFrame(frozen) != frozen; ++frozen) {
      events.push_back({frozen, "freeze", -1, "",
                        "output repeats frame " + std::to_string(sensor->ShownFrame(frozen)) +
                            " (FFC shutter closed)"});
    }
  }
  std::stable_sort(events.begin(), events.end(),
                   [](const DatasetEvent& a, const DatasetEvent& b) { return a.frame < b.frame; });
  WriteDatasetFile(dir, "poses.csv", PosesToCsv(poses), &manifest);
  WriteDatasetFile(dir, "poses_tum.txt", PosesToTum(poses),
                   &manifest);
  WriteDatasetFile(dir, "persons.json", PersonsToJson(persons), &manifest);
  WriteDatasetFile(dir, "events.json", EventsToJson(events), &manifest);
  WriteDatasetFile(dir, "footprints.json", FootprintsToJson(FootprintRecordsOf(world.obstacles())),
                   &manifest);
  WriteDatasetFile(dir, "scene.json", scene.resolved.dump(2), &manifest);
  manifest.complete = true;
  WriteFileAtomic(manifest_path, manifest.ToJson());
  result.complete = true;
  result.video_seconds = video_s;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace hoilcd
