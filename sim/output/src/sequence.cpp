#include "hoilcd/sim/output/sequence.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/dataset/dataset_folder.h"
#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/dataset/video.h"
#include "hoilcd/core/util/allocator.h"
#include "hoilcd/core/util/folder_lock.h"
#include "hoilcd/core/util/memory.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/progress.h"
#include "hoilcd/core/util/sizes.h"
#include "hoilcd/sim/output/frame_writer.h"
#include "hoilcd/sim/output/video_files.h"
#include "hoilcd/sim/render/renderer.h"
#include "hoilcd/sim/render/visibility.h"
#include "hoilcd/sim/scene/scene_options.h"
#include "hoilcd/sim/sensor/sensor.h"

namespace hoilcd {
namespace {

namespace fs = std::filesystem;

std::string FramePath(const char* folder, int frame, const char* extension) {
  return std::string(folder) + "/" + FrameFileName(frame, extension);
}

// The per-frame files of frame f that `outputs` asks for.
std::vector<std::string> FrameFiles(const DatasetOutputs& outputs, int frame) {
  std::vector<std::string> files;
  if (outputs.thermal) files.push_back(FramePath("thermal", frame, "png"));
  if (outputs.radiometric) files.push_back(FramePath("radiometric", frame, "png"));
  if (outputs.exr) files.push_back(FramePath("exr", frame, "exr"));
  return files;
}

// A frame counts as done when each of its files is listed and matches its checksum (and it has
// at least one: without per-frame outputs, every frame is rendered again).
bool FrameDone(const std::string& dir, const DatasetManifest& manifest, int frame) {
  const std::vector<std::string> files = FrameFiles(manifest.outputs, frame);
  if (files.empty()) return false;
  for (const std::string& rel : files) {
    const auto it = manifest.files.find(rel);
    if (it == manifest.files.end()) return false;
    std::error_code ec;
    if (!fs::exists(dir + "/" + rel, ec)) return false;
    if (ChecksumOfFile(dir + "/" + rel) != it->second) return false;
  }
  return true;
}

}  // namespace

SequenceOptions::SequenceOptions() { Table().FillDefaults(this); }

const OptionTable<SequenceOptions>& SequenceOptions::Table() {
  using O = SequenceOptions;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("output_dir", &O::output_dir, "", {}, "dataset folder (created if missing)")
          .Rule("output_dir", [](const O& o) { return o.output_dir.empty() ? "an output folder is required" : ""; })
          .Add("frames", &O::frames, 0, "frames", OptionRange::Closed(0, kMaxFrames),
               "render only the first N frames (0: the scene's count)")
          .Add("threads", &O::threads, 0, "", OptionRange().AtLeast(0),
               "worker threads (0: the CPUs this process may use)")
          .Add("checkpoint_every_frames", &O::checkpoint_every_frames, 25, "frames", OptionRange().AtLeast(1),
               "the manifest is rewritten this often (resume granularity)")
          .Add("outputs", &O::outputs, "thermal,radiometric,exr,video,persons", {},
               "comma-separated outputs to write: thermal, radiometric, exr, video, persons")
          .Rule("outputs", [](const O& o) {
            DatasetOutputs parsed;
            return DatasetOutputs::Parse(o.outputs, &parsed);
          });
  return table;
}

std::string SequenceOptions::Check() const {
  if (std::string problem = Table().FirstProblem(*this); !problem.empty()) return problem;
  if (shard && !shard->Check().empty()) return "shard: " + shard->Check();
  return "";
}

// Bump when a change alters rendered bytes; CHANGELOG.md lists what each revision changed.
constexpr int kSimulatorRevision = 22;

std::string SimulatorVersion() { return std::string(HOILCD_VERSION) + "+sim" + std::to_string(kSimulatorRevision); }

namespace {

// One call of RenderSequence, in named steps: OpenOrResume, then per frame ReuseFrame or
// RenderFrame + WriteFrame (with a Checkpoint every few frames), then Finish. Frames are encoded
// and written by a FrameWriter on every core while the next ones render.
// What every render sets up (and checks) after the world and the robot's run, before its first
// frame: the crowd's plan over the run, and the camera's, video's and renderer's options.
struct FrameSetUp {
  SensorOptions sensor;
  VideoOptions video;
  RenderOptions render;
};
FrameSetUp SetUpFrames(const Scene& scene, World* world, const RobotRun& run, int threads) {
  world->PlanCrowd(run.samples);
  return {SensorOptionsFromScene(scene), VideoOptionsFromScene(scene), RenderOptionsFromScene(scene, threads)};
}

// One recording run of the sequence (the whole sequence when the scene has no runs): its scene,
// world, robot run and camera, and where its frames lie in the sequence.
struct RunRender {
  Scene scene;  // SceneOfRun
  std::unique_ptr<World> world;
  RobotRun run;
  std::unique_ptr<FrameRenderer> renderer;
  std::unique_ptr<SensorModel> sensor;  // switched on at the run's first frame
  int sensor_frame = -1;                // the run's last frame the sensor has seen
  int first_frame = 0;                  // in the sequence
  int frames = 0;                       // its frames in the sequence (--frames may cut the last)
  int person_id_offset = 0;             // its people's ids in the dataset are their own plus this
};

int RunCount(const Scene& scene) { return scene.runs.empty() ? 1 : static_cast<int>(scene.runs.size()); }

// Run k's scene, world, robot run among its obstacles and the crowd's plan (in that order: each
// may throw the InputError that stops a render before its first frame).
FrameSetUp PlanRun(const Scene& scene, int k, const BandRadianceTable& table, int threads, RunRender* r) {
  try {
    r->scene = SceneOfRun(scene, k);
    r->world = std::make_unique<World>(r->scene, table, threads);
    r->run = SimulateSceneRobot(r->scene, r->world->obstacles());
    return SetUpFrames(r->scene, r->world.get(), r->run, threads);
  } catch (const InputError& e) {
    throw LocatedInRun(scene, k, e);
  }
}

// The first run's class ids number the EXR's class channel of every run.
void CheckClassesOfRun(const Scene& scene, const RunRender& first, const RunRender& r, int k) {
  if (r.world->classes() == first.world->classes()) return;
  throw InputError(scene.file + ": /runs/" + std::to_string(k),
                   "its objects give the EXR's class channel other ids than the first run's (one list serves every "
                   "run); place the same kinds of objects in every run");
}

// "" with one run; "run K: " before what belongs to run K of several.
std::string RunPrefix(size_t k, size_t runs) { return runs > 1 ? "run " + std::to_string(k) + ": " : ""; }

class SequenceRender {
 public:
  SequenceRender(const Scene& scene, const SequenceOptions& options)
      : scene_(scene),
        options_(options),
        dir_(options.output_dir),
        manifest_path_(options.output_dir + "/manifest.json"),
        frames_(options.frames > 0 ? std::min(options.frames, scene.frames) : scene.frames),
        range_(options.shard ? ContiguousPart(*options.shard, frames_) : IndexRange{0, frames_}),
        manifest_shard_(options.shard ? std::optional<DatasetShard>({*options.shard, range_.begin, range_.end})
                                      : std::nullopt),
        outputs_(ParseOutputs(options.outputs)),
        intrinsics_(IntrinsicsFromScene(scene)) {
    FrameSetUp set_up;
    runs_.reserve(static_cast<size_t>(RunCount(scene)));  // a run's world may refer to its scene: never moved
    for (int k = 0, first = 0, person_ids = 0; k < RunCount(scene) && first < frames_; ++k) {
      RunRender& r = runs_.emplace_back();
      set_up = PlanRun(scene, k, table_, options.threads, &r);
      CheckClassesOfRun(scene, runs_.front(), r, k);
      r.first_frame = first;
      r.frames = std::min(r.scene.frames, frames_ - first);
      HOILCD_CHECK(static_cast<int>(r.run.samples.size()) >= r.frames);
      r.renderer = std::make_unique<FrameRenderer>(*r.world, intrinsics_, set_up.render);
      r.person_id_offset = person_ids;
      for (const Person& p : r.world->people()) person_ids = std::max(person_ids, r.person_id_offset + p.person_id + 1);
      run_of_frame_.insert(run_of_frame_.end(), static_cast<size_t>(r.frames), k);
      first += r.frames;
    }
    sensor_options_ = set_up.sensor;
    video_options_ = set_up.video;
    // thermal.mp4 is encoded when it is an output, or to make video mode's thermal PNGs; from
    // every frame, so a shard leaves it to the merge, which reads its uncompressed frames.
    encode_video_ = !options.shard && (outputs_.video || (video_options_.enabled && outputs_.thermal));
    if (options.shard && outputs_.video && !outputs_.thermal && !outputs_.exr) {
      throw InputError("--shard", "with --outputs " + outputs_.ToText() +
                                      " a shard keeps no frames that hoilcd merge could encode thermal.mp4 from; "
                                      "add thermal or exr to --outputs");
    }
    for (RunRender& r : runs_) r.sensor = NewSensor(r);
  }

  SequenceResult Run() {
    CheckFramesInFlightFit(ResolveThreadCount(options_.threads));
    OpenOrResume();
    result_.frames_total = range_.end - range_.begin;
    result_.warnings = scene_.warnings;
    for (size_t k = 0; k < runs_.size(); ++k) {
      for (const std::string& w : runs_[k].world->warnings()) result_.warnings.push_back(RunPrefix(k) + w);
    }
    persons_.resize(frames_);
    ProgressReporter progress("render", range_.end - range_.begin, "frames");
    // thermal.mp4 is encoded from the uncompressed 8-bit frames in frame order: while they are
    // written when every frame is rendered by this call, else at the end from the EXRs on disk.
    // Both feed the encoder the same frames, so a resumed render gives the same file.
    if (encode_video_ && !any_done_) {
      streaming_video_ =
          std::make_unique<VideoEncoder>(video_options_, intrinsics_.width, intrinsics_.height, scene_.frame_rate_hz);
    }
    FrameWriterOptions writer_options;
    writer_options.dir = dir_;
    writer_options.display_min_c = sensor_options_.display_min_c;
    writer_options.display_max_c = sensor_options_.display_max_c;
    writer_options.workers = ResolveThreadCount(options_.threads);
    writer_options.thermal = outputs_.thermal;
    writer_options.radiometric = outputs_.radiometric;
    writer_options.exr = outputs_.exr;
    writer_ = std::make_unique<FrameWriter>(writer_options, &manifest_, streaming_video_.get());
    for (int f = range_.begin; f < range_.end; ++f) {
      if ((options_.cancel && options_.cancel->load()) || f - range_.begin == options_.cancel_after_frames) {
        writer_->Finish();
        WriteFileAtomic(manifest_path_, manifest_.ToJson());
        throw RenderInterrupted("interrupted after " + std::to_string(f - range_.begin) +
                                " frames; re-run the same command to resume");
      }
      RunRender& r = RunOf(f);
      r.world->SetTime(r.run.samples[f - r.first_frame].time_s);
      if (done_[f]) {
        ReuseFrame(f);
      } else {
        WriteFrame(RenderFrame(f));
      }
      progress.Update();
    }
    writer_->Finish();
    result_.video_seconds += writer_->video_seconds();
    progress.Done();
    Finish();
    return result_;
  }

 private:
  // The frames the writer may hold (2 per encoder thread) and the one rendering, each its
  // temperature image and EXR channels (T, T_true, Z, ids: about 26 bytes a pixel, 32 with the
  // renderer's buffers), against this process's memory: a large camera at many threads is
  // refused by name before the first frame.
  void CheckFramesInFlightFit(int workers) const {
    constexpr double kBytesPerPixel = 32;
    const double frames = 2.0 * workers + 2;
    CheckAllocation(frames * intrinsics_.width * intrinsics_.height * kBytesPerPixel, "--threads",
                    "rendering " + std::to_string(workers) + " threads' frames in flight (" +
                        std::to_string(static_cast<int>(frames)) + " frames of " + std::to_string(intrinsics_.width) +
                        " x " + std::to_string(intrinsics_.height) + " px, /camera/width_px and /camera/height_px)");
  }

  // "shard I/N" or "a whole sequence", for messages.
  static std::string ShardText(const std::optional<DatasetShard>& shard) {
    return shard ? "shard " + shard->shard.Name() : "a whole sequence (rendered without --shard)";
  }

  static DatasetOutputs ParseOutputs(const std::string& text) {
    DatasetOutputs outputs;
    HOILCD_CHECK(DatasetOutputs::Parse(text, &outputs).empty());  // SequenceOptions::Check ran
    return outputs;
  }

  // The camera of run r, as switched on at its first frame: its fixed pattern the scene's, its
  // noise and drift the run's.
  std::unique_ptr<SensorModel> NewSensor(const RunRender& r) const {
    return std::make_unique<SensorModel>(sensor_options_, intrinsics_.width, intrinsics_.height, scene_.frame_rate_hz,
                                         scene_.seed, &table_, options_.threads, r.scene.run_seed);
  }

  RunRender& RunOf(int frame) { return runs_[static_cast<size_t>(run_of_frame_[static_cast<size_t>(frame)])]; }

  std::string RunPrefix(size_t k) const { return hoilcd::RunPrefix(k, runs_.size()); }

  // The people of run r that frame f sees, with their ids in the dataset.
  FramePersons PersonsOf(const RunRender& r, int f, const CameraPose& camera, const cv::Mat& ids,
                         const cv::Mat& depth) const {
    FramePersons persons{f, VisiblePersons(*r.world, intrinsics_, camera, ids, depth, options_.threads)};
    for (PersonRecord& p : persons.persons) p.id += r.person_id_offset;
    return persons;
  }

  // An existing folder must be an earlier run of this very render (scene, seed, frame count,
  // shard, outputs); anything else is the user's. Under the folder's lock, held until the render
  // ends: a second render of the folder is refused by name. Marks the frames an earlier run
  // finished (done_) and writes the first manifest.
  void OpenOrResume() {
    lock_.emplace(dir_, FolderLock::IfBusy::kRefuse);
    std::error_code ec;
    if (fs::exists(manifest_path_, ec)) {
      DatasetManifest old = DatasetManifest::FromJson(ReadFileBytes(manifest_path_), manifest_path_);
      if (old.hoilcd_version != SimulatorVersion()) {
        throw InputError(dir_, "holds a dataset rendered by hoilcd " + old.hoilcd_version + " (this is " +
                                   SimulatorVersion() +
                                   "), whose frames would not match new ones; delete it or choose another "
                                   "output folder");
      }
      if (old.scene_hash != scene_.hash || old.seed != scene_.seed) {
        throw InputError(dir_, "holds a dataset of another scene or seed (scene hash " + old.scene_hash + ", seed " +
                                   std::to_string(old.seed) + "); choose another output folder or delete this one");
      }
      if (old.frame_count != frames_) {
        throw InputError(dir_, "holds a dataset of " + std::to_string(old.frame_count) +
                                   " frames (this render asks for " + std::to_string(frames_) +
                                   ", from --frames or the scene's frames); use the same --frames, another output "
                                   "folder, or delete this one");
      }
      if (ShardText(old.shard) != ShardText(manifest_shard_)) {
        throw InputError(dir_, "holds " + ShardText(old.shard) + " (this render asks for " +
                                   ShardText(manifest_shard_) +
                                   "); use the same --shard, another "
                                   "output folder, or delete this one");
      }
      if (old.outputs != outputs_) {
        throw InputError(dir_, "holds a dataset with --outputs " + old.outputs.ToText() + " (this render asks for " +
                                   outputs_.ToText() +
                                   "); use the same --outputs, another output folder, or "
                                   "delete this one");
      }
      manifest_ = old;
    } else if (const std::vector<std::string> files = NonTempFiles(dir_); !files.empty()) {
      // Only temp files of a run killed before its first manifest may be there: any other file,
      // even one named like a dataset file (scene.json, poses.csv), is the user's.
      throw InputError(dir_, "exists, is not empty and is not a hoilcd dataset (it holds " + JoinFileList(files) +
                                 " and no manifest.json); refusing to overwrite files in it: choose a new or "
                                 "empty folder");
    }
    // A killed run may leave temp files of atomic writes ("NAME.tmp.PID"); they were never
    // renamed into place, so nothing refers to them. Only those exact names are removed.
    RemoveDatasetTempFiles(dir_);

    manifest_.hoilcd_version = SimulatorVersion();
    manifest_.scene_hash = scene_.hash;
    manifest_.seed = scene_.seed;
    manifest_.intrinsics = intrinsics_;
    manifest_.frame_rate_hz = scene_.frame_rate_hz;
    manifest_.frame_count = frames_;
    manifest_.window_min_c = sensor_options_.display_min_c;
    manifest_.window_max_c = sensor_options_.display_max_c;
    manifest_.classes = runs_.front().world->classes();
    manifest_.outputs = outputs_;
    manifest_.complete = false;
    manifest_.shard = manifest_shard_;

    done_.assign(frames_, false);
    // The video of a resumed render is made from the kept frames' EXRs, else from their thermal
    // PNGs outside video mode; with neither, every frame is rendered again.
    const bool video_from_disk = outputs_.exr || (outputs_.thermal && !video_options_.enabled);
    for (int f = range_.begin; f < range_.end && (video_from_disk || !encode_video_); ++f) {
      done_[f] = FrameDone(dir_, manifest_, f);
      any_done_ = any_done_ || done_[f];
    }
    // Drop listings of files that are not (or no longer) valid frames or side files.
    for (auto it = manifest_.files.begin(); it != manifest_.files.end();) {
      bool keep = false;
      for (int f = range_.begin; f < range_.end && !keep; ++f) {
        const std::vector<std::string> files = FrameFiles(outputs_, f);
        keep = done_[f] && std::find(files.begin(), files.end(), it->first) != files.end();
      }
      it = keep ? std::next(it) : manifest_.files.erase(it);
    }
    WriteFileAtomic(manifest_path_, manifest_.ToJson());
  }

  // Kept from an earlier run: ground truth comes from its stored instance ids and depth, or
  // without EXRs from the frame's ids and depth cast again (no sensor model needed).
  void ReuseFrame(int f) {
    ++result_.frames_reused;
    if (!outputs_.persons) return;
    const RunRender& r = RunOf(f);
    const CameraPose& camera = r.run.samples[f - r.first_frame].camera;
    cv::Mat ids, depth;
    if (outputs_.exr) {
      for (const auto& [name, channel] :
           ReadExr(dir_ + "/" + FramePath("exr", f, "exr"), {intrinsics_.width, intrinsics_.height})) {
        if (name == "id") channel.convertTo(ids, CV_32S);
        if (name == "Z") channel.convertTo(depth, CV_32F);
      }
    } else {
      const FrameBuffers buffers = r.renderer->Render(camera);
      ids = buffers.instance;
      depth = StoredDepth(buffers.depth_m);
    }
    if (!ids.empty()) persons_[f] = PersonsOf(r, f, camera, ids, depth);
  }

  // The depth as the EXR stores it (half), which the persons' ground truth reads, so that a
  // resumed frame's ground truth is that of a fresh one.
  static cv::Mat StoredDepth(const cv::Mat& depth_m) {
    cv::Mat half, back;
    depth_m.convertTo(half, CV_16F);
    half.convertTo(back, CV_32F);
    return back;
  }

  // Ray casts frame f (the world is at its time), applies the sensor model and finds the
  // visible people.
  FrameImages RenderFrame(int f) {
    RunRender& r = RunOf(f);
    const int local = f - r.first_frame;  // the run's own frame: its sensor's
    const RobotSample& sample = r.run.samples[local];
    if (local > 0 && r.sensor_frame != local - 1) {
      // Resuming after kept frames: a fresh model replays the frames its state depends on (the
      // previous frame; during an FFC freeze, back to the frame it shows): the resume contract.
      r.sensor = NewSensor(r);
      for (int replay = r.sensor->ReplayFrom(local); replay < local; ++replay) {
        r.world->SetTime(r.run.samples[replay].time_s);
        r.sensor->Apply(replay, r.renderer->Render(r.run.samples[replay].camera).radiance);
      }
      r.world->SetTime(sample.time_s);
    }
    const FrameBuffers buffers = r.renderer->Render(sample.camera);
    FrameImages out;
    out.frame = f;
    out.temperature_c = r.sensor->Apply(local, buffers.radiance);
    r.sensor_frame = local;
    if (outputs_.exr) {
      out.exr = FrameExrChannels(out.temperature_c, r.sensor->IdealTemperature(buffers.radiance), buffers.depth_m,
                                 buffers.instance, buffers.class_id);
    }
    if (outputs_.persons) persons_[f] = PersonsOf(r, f, sample.camera, buffers.instance, StoredDepth(buffers.depth_m));
    return out;
  }

  // Hands the frame to the writer (waiting only while its queue is full); every
  // checkpoint_every_frames frames, a resume point.
  void WriteFrame(FrameImages frame) {
    writer_->Submit(std::move(frame));
    ++result_.frames_rendered;
    if (++since_checkpoint_ >= options_.checkpoint_every_frames) {
      writer_->Checkpoint();
      since_checkpoint_ = 0;
    }
  }

  // The first run's obstacles, then those of later runs that are not the first's (people standing
  // elsewhere), each named "run K: NAME".
  std::vector<FootprintRecord> Footprints() const {
    const auto same = [](const FootprintRecord& a, const FootprintRecord& b) {
      return a.name == b.name && a.kind == b.kind && a.centre_m == b.centre_m && a.half_size_m == b.half_size_m &&
             a.yaw_deg == b.yaw_deg && a.radius_m == b.radius_m;
    };
    const std::vector<FootprintRecord> first = FootprintRecordsOf(runs_.front().world->obstacles());
    std::vector<FootprintRecord> footprints = first;
    for (size_t k = 1; k < runs_.size(); ++k) {
      for (FootprintRecord f : FootprintRecordsOf(runs_[k].world->obstacles())) {
        if (std::any_of(first.begin(), first.end(), [&](const FootprintRecord& g) { return same(f, g); })) continue;
        f.name = RunPrefix(k) + f.name;
        footprints.push_back(std::move(f));
      }
    }
    return footprints;
  }

  // runs.json: where each run's frames lie and when it was recorded.
  std::vector<RunRecord> RunRecords() const {
    std::vector<RunRecord> records;
    for (size_t k = 0; k < runs_.size(); ++k) {
      const RunSpec& spec = scene_.runs[k];
      records.push_back(
          {runs_[k].first_frame, runs_[k].frames, spec.time_of_day_h, spec.day, spec.start_time_s, spec.seed});
    }
    return records;
  }

  // The video; in video mode its decoded frames become the thermal PNGs that methods read.
  void WriteVideo() {
    const auto video_start = std::chrono::steady_clock::now();
    std::string mp4;
    if (streaming_video_ && streaming_video_->frames_added() == frames_) {
      mp4 = streaming_video_->Finish();
    } else {
      mp4 = EncodeVideo(video_options_, manifest_, frames_,
                        [&](int f) { return UncompressedFrame(dir_, f, manifest_, outputs_.exr); });
    }
    WriteVideoFiles(dir_, mp4, video_options_, frames_, options_.threads, &manifest_);
    video_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - video_start).count();
  }

  // thermal.mp4, the side files, then the manifest that declares the dataset complete. A shard
  // writes the whole sequence's poses, events and footprints (the same in every shard: its world
  // was planned for all frames) and persons.json of its own frames.
  void Finish() {
    if (encode_video_) WriteVideo();
    std::vector<PoseRecord> poses;
    std::vector<DatasetEvent> events;
    for (size_t k = 0; k < runs_.size(); ++k) {
      const RunRender& r = runs_[k];
      for (PoseRecord p : PoseRecordsOf(r.run, r.frames)) {
        p.frame += r.first_frame;
        p.time_s += r.scene.clock_offset_s;  // the run's start after the first run's
        p.run = static_cast<int>(k);
        poses.push_back(p);
      }
      std::vector<DatasetEvent> run_events;
      for (DatasetEvent e : r.world->events()) {
        if (e.frame >= r.frames) continue;
        e.frame += r.first_frame;
        e.person += r.person_id_offset;
        run_events.push_back(std::move(e));
      }
      // The sensor's frames are the run's own; the shown frame of a freeze is named in the sequence.
      for (int f : r.sensor->FfcFrames(r.frames)) {
        run_events.push_back({r.first_frame + f, "ffc", -1, "", "flat-field correction (shutter)"});
        for (int frozen = f; frozen < r.frames && r.sensor->ShownFrame(frozen) != frozen; ++frozen) {
          run_events.push_back({r.first_frame + frozen, "freeze", -1, "",
                                "output repeats frame " + std::to_string(r.first_frame + r.sensor->ShownFrame(frozen)) +
                                    " (FFC shutter closed)"});
        }
      }
      std::stable_sort(run_events.begin(), run_events.end(),
                       [](const DatasetEvent& a, const DatasetEvent& b) { return a.frame < b.frame; });
      events.insert(events.end(), run_events.begin(), run_events.end());
    }
    WriteDatasetFile(dir_, "poses.csv", PosesToCsv(poses), &manifest_);
    WriteDatasetFile(dir_, "poses_tum.txt", PosesToTum(poses), &manifest_);
    if (outputs_.persons) {
      const std::vector<FramePersons> persons(persons_.begin() + range_.begin, persons_.begin() + range_.end);
      WriteDatasetFile(dir_, "persons.json", PersonsToJson(persons, options_.threads), &manifest_);
    }
    WriteDatasetFile(dir_, "events.json", EventsToJson(events), &manifest_);
    WriteDatasetFile(dir_, "footprints.json", FootprintsToJson(Footprints()), &manifest_);
    WriteDatasetFile(dir_, "scene.json", scene_.resolved.dump(2), &manifest_);
    if (!scene_.runs.empty()) WriteDatasetFile(dir_, "runs.json", RunsToJson(RunRecords()), &manifest_);
    manifest_.complete = true;
    WriteFileAtomic(manifest_path_, manifest_.ToJson());
    result_.complete = true;
    result_.video_seconds += video_s_;
  }

  const Scene& scene_;
  const SequenceOptions& options_;
  const std::string dir_;
  const std::string manifest_path_;
  const int frames_;                                  // of the sequence
  const IndexRange range_;                            // the frames this render writes: all, or its shard's
  const std::optional<DatasetShard> manifest_shard_;  // what the manifest says of the shard (none: whole)
  const DatasetOutputs outputs_;
  const BandRadianceTable table_;
  const CameraIntrinsics intrinsics_;
  std::vector<RunRender> runs_;    // those the frames reach
  std::vector<int> run_of_frame_;  // the run of each frame
  SensorOptions sensor_options_;
  VideoOptions video_options_;

  DatasetManifest manifest_;
  std::vector<bool> done_;  // frames kept from an earlier run
  bool any_done_ = false;
  std::vector<FramePersons> persons_;
  int since_checkpoint_ = 0;
  bool encode_video_ = true;  // thermal.mp4 is an output or makes video mode's thermal PNGs
  std::unique_ptr<VideoEncoder> streaming_video_;
  double video_s_ = 0.0;  // thermal.mp4 outside the writer
  SequenceResult result_;
  std::optional<FolderLock> lock_;  // the output folder's, from OpenOrResume on; let go after the writer stops
  // Last, so it is destroyed (stopping its workers) before the manifest and video it writes to.
  std::unique_ptr<FrameWriter> writer_;
};

}  // namespace

std::vector<std::string> CheckSceneRenders(const Scene& scene) {
  // SequenceRender's set-up, in its order: the camera, then each run's world, robot run and crowd.
  const BandRadianceTable table;
  IntrinsicsFromScene(scene);
  std::vector<std::string> warnings = scene.warnings;
  std::vector<RunRender> runs(static_cast<size_t>(RunCount(scene)));
  for (size_t k = 0; k < runs.size(); ++k) {
    PlanRun(scene, static_cast<int>(k), table, 1, &runs[k]);
    CheckClassesOfRun(scene, runs.front(), runs[k], static_cast<int>(k));
    for (const std::string& w : runs[k].world->warnings()) warnings.push_back(RunPrefix(k, runs.size()) + w);
  }
  return warnings;
}

SequenceResult RenderSequence(const Scene& scene, const SequenceOptions& options) {
  if (const std::string problem = options.Check(); !problem.empty()) throw InputError("render", problem);
  KeepFreedMemoryForReuse();  // frames are allocated here and freed by the writer's threads
  const auto start = std::chrono::steady_clock::now();
  SequenceResult result = SequenceRender(scene, options).Run();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace hoilcd
