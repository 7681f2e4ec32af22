// hoilcd.render, hoilcd.bench, hoilcd.evaluate and hoilcd.methods: the command line's render,
// bench and evaluate as functions; the long C++ work runs without the GIL.
#include <optional>

#include <pybind11/stl.h>

#include "bindings.h"
#include "hoilcd/bench/evaluation/evaluate.h"
#include "hoilcd/bench/methods/loop_closure_method.h"
#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/bench/report/report.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/sim/output/sequence.h"
#include "hoilcd/sim/scene/scene.h"

namespace hoilcd::python {

namespace {

// {"crowd.people_per_table": 2} -> ["crowd.people_per_table=2"], as --set takes them; strings
// are passed as written, other values as JSON.
std::vector<std::string> Overrides(const py::dict& values) {
  std::vector<std::string> out;
  for (const auto& [key, value] : values) {
    const std::string text = py::isinstance<py::str>(value) ? value.cast<std::string>() : PythonToJson(value);
    out.push_back(py::str(key).cast<std::string>() + "=" + text);
  }
  return out;
}

Dataset Render(const std::string& scene_path, const std::string& output, int frames, std::optional<int64_t> seed,
               const py::dict& set, int threads) {
  std::vector<std::string> overrides = Overrides(set);
  if (seed) {
    if (*seed < 0) throw InputError("seed", "a non-negative integer; got " + std::to_string(*seed));
    overrides.push_back("seed=" + std::to_string(*seed));
  }
  SequenceOptions options;
  options.output_dir = output;
  options.frames = frames;
  options.threads = threads;
  if (const std::string problem = options.Check(); !problem.empty()) throw InputError("render options", problem);
  py::gil_scoped_release unlocked;
  const Scene scene = LoadScene(scene_path, overrides);
  RenderSequence(scene, options);
  return Dataset::Open(output, Verify::kOnRead);
}

ProtocolOptions Protocol(const std::string& protocol, const std::string& ground_truth, double radius_m,
                         double exclusion_window_s, double heading_tolerance_deg) {
  ProtocolOptions o;
  o.protocol = protocol;
  o.ground_truth = ground_truth;
  o.radius_m = radius_m;
  o.exclusion_window_s = exclusion_window_s;
  o.heading_tolerance_deg = heading_tolerance_deg;
  if (const std::string problem = o.Check(); !problem.empty()) throw InputError("protocol", problem);
  return o;
}

// The metrics of one method's dense frames x frames scores (NaN = unscored), as report.json's
// methods.<name>; with `output`, its report folder is written there (as hoilcd evaluate -o).
py::object EvaluateScores(const Dataset& dataset, py::array_t<double, py::array::c_style | py::array::forcecast> scores,
                          const std::string& name, std::optional<std::string> output, const std::string& protocol,
                          const std::string& ground_truth, double radius_m, double exclusion_window_s,
                          double heading_tolerance_deg) {
  if (name.empty()) throw InputError("name", "a method name for the report");
  const ProtocolOptions options = Protocol(protocol, ground_truth, radius_m, exclusion_window_s, heading_tolerance_deg);
  if (scores.ndim() != 2 || scores.shape(0) != scores.shape(1)) {
    std::string shape;
    for (py::ssize_t d = 0; d < scores.ndim(); ++d) shape += (d ? ", " : "") + std::to_string(scores.shape(d));
    throw InputError("scores", "a frames x frames matrix (" + std::to_string(dataset.num_frames()) + " x " +
                                   std::to_string(dataset.num_frames()) + "); got shape (" + shape + ")");
  }
  ScoreMatrix matrix;
  matrix.frames = static_cast<int>(scores.shape(0));
  matrix.values.assign(scores.data(), scores.data() + scores.size());
  const std::string description = "scores from Python";
  std::string report_json;
  std::vector<std::string> warnings;
  {
    py::gil_scoped_release unlocked;
    if (output) CheckReportFolder(*output);  // a folder the report may not use fails before the work
    const Labelling labelling = LabelQueries(dataset, options);
    const MethodReport report = output ? EvaluateAndWriteReport(dataset, labelling, matrix, name, description, *output)
                                       : EvaluateLabelled(dataset, labelling, matrix, name);
    report_json = EvaluateReportJson(dataset, options, report, description)["methods"][report.name].dump();
    warnings = report.warnings;
  }
  for (const std::string& warning : warnings) {  // as `hoilcd evaluate` prints them
    if (PyErr_WarnEx(PyExc_UserWarning, warning.c_str(), 1) != 0) throw py::error_already_set();
  }
  return JsonToPython(report_json);
}

py::dict Bench(const Dataset& dataset, std::optional<std::vector<std::string>> methods,
               std::optional<std::string> output, const std::string& protocol, const std::string& ground_truth,
               double radius_m, int threads) {
  BenchOptions options;
  options.methods = options.optional_methods = DefaultMethods();  // as the command line's
  if (methods) {
    std::string csv;
    for (const std::string& name : *methods) csv += (csv.empty() ? "" : ",") + name;
    options.methods = ParseMethodList(csv, &options.optional_methods);
  }
  options.protocol = Protocol(protocol, ground_truth, radius_m, options.protocol.exclusion_window_s,
                              options.protocol.heading_tolerance_deg);
  options.threads = threads;
  if (const std::string problem = options.Check(); !problem.empty()) throw InputError("bench options", problem);
  std::string report_json;
  {
    py::gil_scoped_release unlocked;
    const BenchResult result = RunBench(dataset, options);
    if (output) {
      ReportTiming timing;
      timing.bench_s = result.seconds;
      WriteReport(result, dataset, options, timing, *output);
      report_json = ReadFileBytes(*output + "/report.json");
    } else {
      report_json = ResultsJson(result, options).dump();  // the command line's report.json, its results
    }
  }
  return JsonToPython(report_json);
}

}  // namespace

void BindRun(py::module_& m) {
  const ProtocolOptions defaults = ProtocolOptions();  // the protocol's defaults, as the command line's
  m.def("render", &Render, py::arg("scene"), py::arg("output"), py::arg("frames") = 0, py::arg("seed") = py::none(),
        py::arg("set") = py::dict(), py::arg("threads") = 0,
        "Renders SCENE (a scene file) into the dataset folder OUTPUT, as `hoilcd render`: the first "
        "`frames` frames (0: all), `seed` overriding the scene's, `set` overriding scene values by path "
        "({'crowd.people_per_table': 2}). Resumes an interrupted render. Returns the Dataset.");
  m.def("bench", &Bench, py::arg("dataset"), py::arg("methods") = py::none(), py::arg("output") = py::none(),
        py::arg("protocol") = defaults.protocol, py::arg("ground_truth") = defaults.ground_truth,
        py::arg("radius_m") = defaults.radius_m, py::arg("threads") = 0,
        "Runs the built-in methods (names as `hoilcd bench --methods`; default: all) on a Dataset. With "
        "`output`, writes the report folder there and returns report.json as a dict; otherwise returns "
        "{'protocol': ..., 'methods': {name: metrics}} with the metrics as in report.json.");
  m.def("evaluate", &EvaluateScores, py::arg("dataset"), py::arg("scores"), py::arg("name") = "python",
        py::arg("output") = py::none(), py::arg("protocol") = defaults.protocol,
        py::arg("ground_truth") = defaults.ground_truth, py::arg("radius_m") = defaults.radius_m,
        py::arg("exclusion_window_s") = defaults.exclusion_window_s,
        py::arg("heading_tolerance_deg") = defaults.heading_tolerance_deg,
        "The benchmark's protocol, labels and metrics applied to your method, as `hoilcd evaluate`: `scores` "
        "is a dense frames x frames numpy matrix (scores[query, reference], higher = more alike, NaN = "
        "unscored). Returns the method's metrics as report.json's methods.<name> (mrr, recall_at_1, ...); "
        "with `output`, also writes the report folder there, as `hoilcd evaluate -o` (report.json, "
        "queries.csv, report.md, figures; a new or empty folder, or an earlier report's).");
  m.def(
      "methods",
      [] {
        py::list out;
        for (const auto& method : RegisteredMethods()) {
          out.append(py::dict(py::arg("name") = method->Name(), py::arg("description") = method->Description(),
                              py::arg("from_paper") = method->FromPaper()));
        }
        return out;
      },
      "The built-in methods hoilcd.bench can run: a list of {name, description, from_paper}.");
}

}  // namespace hoilcd::python
