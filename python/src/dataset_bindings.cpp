// hoilcd.Dataset: a dataset folder (SPEC.md "Dataset folder") read as numpy arrays and dicts.
#include <map>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/dataset/exr_io.h"

namespace hoilcd::python {
namespace {

// Python index (negative counts from the end) -> frame; IndexError outside the dataset.
int FrameIndex(const Dataset& dataset, int64_t index) {
  const int64_t n = dataset.num_frames();
  const int64_t frame = index < 0 ? index + n : index;
  if (frame < 0 || frame >= n) {
    throw py::index_error("frame " + std::to_string(index) + " outside the dataset's " + std::to_string(n) +
                          " frames (" + dataset.dir() + ")");
  }
  return static_cast<int>(frame);
}

// poses.csv as one array per column, under the column names of the file.
py::dict PosesToDict(const std::vector<PoseRecord>& poses) {
  const std::vector<std::pair<const char*, double PoseRecord::*>> columns = {{"t", &PoseRecord::time_s},
                                                                             {"x", &PoseRecord::x_m},
                                                                             {"y", &PoseRecord::y_m},
                                                                             {"theta", &PoseRecord::theta_rad},
                                                                             {"cam_x", &PoseRecord::cam_x_m},
                                                                             {"cam_y", &PoseRecord::cam_y_m},
                                                                             {"cam_z", &PoseRecord::cam_z_m},
                                                                             {"cam_yaw", &PoseRecord::cam_yaw_rad},
                                                                             {"cam_pitch", &PoseRecord::cam_pitch_rad},
                                                                             {"cam_roll", &PoseRecord::cam_roll_rad},
                                                                             {"odo_x", &PoseRecord::odo_x_m},
                                                                             {"odo_y", &PoseRecord::odo_y_m},
                                                                             {"odo_theta", &PoseRecord::odo_theta_rad}};
  py::dict out;
  py::array_t<int32_t> frames(static_cast<py::ssize_t>(poses.size()));
  for (size_t i = 0; i < poses.size(); ++i) frames.mutable_data()[i] = poses[i].frame;
  out["frame"] = frames;
  for (const auto& [name, member] : columns) {
    py::array_t<double> column(static_cast<py::ssize_t>(poses.size()));
    for (size_t i = 0; i < poses.size(); ++i) column.mutable_data()[i] = poses[i].*member;
    out[name] = column;
  }
  py::array_t<int32_t> runs(static_cast<py::ssize_t>(poses.size()));  // not a poses.csv column: from runs.json
  for (size_t i = 0; i < poses.size(); ++i) runs.mutable_data()[i] = poses[i].run;
  out["run"] = runs;
  return out;
}

py::list PersonsOfFrame(const Dataset& dataset, int frame) {
  for (const FramePersons& f : dataset.persons()) {
    if (f.frame == frame) return JsonToPython(PersonsToJson({f}))["frames"][py::int_(0)]["persons"];
  }
  return py::list();
}

py::dict ExrToDict(const Dataset& dataset, int frame) {
  const ExrChannels channels = ReadDatasetExr(dataset, frame);
  py::dict out;
  for (const auto& [name, image] : channels) out[py::str(name)] = ImageToArray<float>(image);
  return out;
}

}  // namespace

void BindDataset(py::module_& m) {
  py::class_<Dataset>(m, "Dataset", "A dataset folder written by hoilcd render, read as numpy arrays.")
      .def(py::init([](const std::string& path, bool verify_checksums) {
             return Dataset::Open(path, verify_checksums ? Verify::kEveryFile : Verify::kNothing);
           }),
           py::arg("path"), py::arg("verify_checksums") = true,
           "Opens DIR (manifest.json, poses, persons, events); with verify_checksums every file's "
           "checksum is checked first. Raises InputError naming the file on a bad or partial dataset.")
      .def("__len__", &Dataset::num_frames)
      .def_property_readonly("dir", &Dataset::dir)
      .def_property_readonly(
          "manifest", [](const Dataset& d) { return JsonToPython(d.manifest().ToJson()); }, "manifest.json as a dict")
      .def_property_readonly(
          "scene", [](const Dataset& d) { return JsonToPython(d.scene_json()); },
          "the resolved scene (scene.json) as a dict")
      .def_property_readonly(
          "poses", [](const Dataset& d) { return PosesToDict(d.poses()); },
          "poses.csv as {column: numpy array}: frame, t, x, y, theta (robot base, ground "
          "truth; m, rad), cam_*, odo_x, odo_y, odo_theta (wheel odometry), and run (each "
          "frame's recording run, from runs.json; 0 throughout without it)")
      .def_property_readonly(
          "runs", [](const Dataset& d) -> py::list { return JsonToPython(RunsToJson(d.runs()))["runs"]; },
          "the recording runs (runs.json) as a list of dicts: first_frame, frames, "
          "time_of_day_h (-1: not stated), day, start_time_s, seed; one run over every frame "
          "when the dataset has no runs.json")
      .def_property_readonly(
          "events", [](const Dataset& d) { return JsonToPython(EventsToJson(d.events())); },
          "events.json as a list of dicts")
      .def_property_readonly("warnings", &Dataset::warnings)
      .def(
          "thermal", [](const Dataset& d, int64_t i) { return ImageToArray<uint8_t>(d.Thermal(FrameIndex(d, i))); },
          py::arg("frame"), "8-bit thermal image (H x W uint8, linear over the display window)")
      .def(
          "temperature_c",
          [](const Dataset& d, int64_t i) { return ImageToArray<float>(d.RadiometricC(FrameIndex(d, i))); },
          py::arg("frame"), "apparent temperature, °C (H x W float32, from the radiometric PNG)")
      .def(
          "radiometric",
          [](const Dataset& d, int64_t i) {
            return ImageToArray<uint16_t>(d.RadiometricCentikelvin(FrameIndex(d, i)));
          },
          py::arg("frame"), "the radiometric PNG as stored: H x W uint16, centikelvin (K x 100)")
      .def(
          "exr", [](const Dataset& d, int64_t i) { return ExrToDict(d, FrameIndex(d, i)); }, py::arg("frame"),
          "the frame's EXR channels as {name: H x W float32}: T, T_true (°C), Z (m), id, class")
      .def(
          "persons", [](const Dataset& d, int64_t i) { return PersonsOfFrame(d, FrameIndex(d, i)); }, py::arg("frame"),
          "the visible people of a frame (persons.json entries) as a list of dicts")
      .def("__repr__", [](const Dataset& d) {
        return "hoilcd.Dataset('" + d.dir() + "', " + std::to_string(d.num_frames()) + " frames)";
      });
  // Functions taking a Dataset take its folder's path as well.
  py::implicitly_convertible<py::str, Dataset>();
}

}  // namespace hoilcd::python
