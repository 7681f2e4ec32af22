// A dataset of several recording runs joined from datasets rendered apart, each one run: the robot
// starts at its dock with its odometry restarting there, as in a multi-run render. Frames are
// numbered on, times shifted to each run's start, person ids kept unique, runs.json written.
// (Until hoilcd render writes such datasets itself.) thermal.mp4 is left out.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/file_io.h"
#include "tiny_room.h"

namespace hoilcd::test {

struct RunSource {
  std::string dir;           // a dataset folder: the run's frames
  double time_of_day_h = 9;  // h, runs.json's
  int day = 0;
  double start_time_s = 0;  // s since the first run began (the first run: 0)
};

// Writes the joined dataset into `out`; returns `out`.
inline std::string JoinAsRuns(const std::vector<RunSource>& sources, const std::string& out) {
  DatasetManifest m;
  std::vector<PoseRecord> poses;
  std::vector<FramePersons> persons;
  std::vector<DatasetEvent> events;
  std::vector<RunRecord> runs;
  int id_offset = 0;
  for (const RunSource& source : sources) {
    const Dataset d = Dataset::Open(source.dir);
    const int first = static_cast<int>(poses.size());
    if (runs.empty()) {
      m = d.manifest();
      m.files.clear();
      m.outputs.video = false;
      m.complete = false;
      WriteDatasetFile(out, "scene.json", d.scene_json(), &m);
      if (!d.footprints().empty()) WriteDatasetFile(out, "footprints.json", FootprintsToJson(d.footprints()), &m);
    }
    runs.push_back({first, d.num_frames(), source.time_of_day_h, source.day, source.start_time_s, d.manifest().seed});
    for (int f = 0; f < d.num_frames(); ++f) {
      for (const char* output : {"thermal", "radiometric", "exr"}) {
        if (!d.manifest().outputs.Has(output)) continue;
        const char* extension = std::string(output) == "exr" ? "exr" : "png";
        WriteDatasetFile(out, std::string(output) + "/" + FrameFileName(first + f, extension),
                         d.ReadFile(std::string(output) + "/" + FrameFileName(f, extension)), &m);
      }
      PoseRecord p = d.poses()[f];
      p.frame += first;
      p.time_s += source.start_time_s - d.poses().front().time_s;
      poses.push_back(p);
    }
    int max_id = -1;
    if (d.manifest().outputs.persons) {
      for (FramePersons f : d.persons()) {
        f.frame += first;
        for (PersonRecord& p : f.persons) max_id = std::max(max_id, p.id), p.id += id_offset;
        persons.push_back(f);
      }
    }
    for (DatasetEvent e : d.events()) {
      e.frame += first;
      if (e.person >= 0) max_id = std::max(max_id, e.person), e.person += id_offset;
      events.push_back(e);
    }
    id_offset += max_id + 1;
  }
  m.frame_count = static_cast<int>(poses.size());
  WriteDatasetFile(out, "poses.csv", PosesToCsv(poses), &m);
  WriteDatasetFile(out, "poses_tum.txt", PosesToTum(poses), &m);
  if (m.outputs.persons) WriteDatasetFile(out, "persons.json", PersonsToJson(persons), &m);
  WriteDatasetFile(out, "events.json", EventsToJson(events), &m);
  WriteDatasetFile(out, "runs.json", RunsToJson(runs), &m);
  m.complete = true;
  WriteFileAtomic(out + "/manifest.json", m.ToJson());
  return out;
}

// The tiny room recorded twice, `frames` frames each (a lap is ~220): run 0 at 09:00 (seed 1), run 1
// at 14:30 the same day (seed 2: other people and noise). Renders into dir/run0, dir/run1; the
// dataset is dir/runs.
inline Dataset TinyRoomTwoRuns(const std::string& dir, int frames) {
  const std::string count = "frames=" + std::to_string(frames);
  RenderTinyRoom(dir + "/run0", {count, "seed=1"});
  RenderTinyRoom(dir + "/run1", {count, "seed=2"});
  return Dataset::Open(JoinAsRuns({{dir + "/run0", 9.0, 0, 0}, {dir + "/run1", 14.5, 0, 5.5 * 3600}}, dir + "/runs"));
}

}  // namespace hoilcd::test
