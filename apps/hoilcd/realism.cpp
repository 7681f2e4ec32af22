// hoilcd realism DATASET REAL_DIR -o DIR: the statistics that tell a rendered room from a real
// one, on a dataset's frames and on a folder of real thermal frames, and their distances.
#include "hoilcd/bench/realism/realism.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <memory>

#include "command.h"
#include "hoilcd/bench/realism/real_frames.h"
#include "hoilcd/bench/report/realism_report.h"
#include "hoilcd/core/dataset/dataset.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/sizes.h"
#include "shared.h"

namespace hoilcd {
namespace {

struct RealismArgs {
  std::string dataset;
  std::string real_dir;
  std::string output;
  int stride = 1;
  RealFrameOptions real;
  bool static_sequence = false;
  int threads = 0;
  const CLI::Option* float_unit_flag = nullptr;  // given: the folder must hold float frames
};

// Whether `name` may hold float frames (.npy, TIFF): the only ones --float-unit applies to.
bool MayHoldFloats(std::string name) {
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const char* ext : {".npy", ".tif", ".tiff"}) {
    const std::string e(ext);
    if (name.size() >= e.size() && name.compare(name.size() - e.size(), e.size(), e) == 0) return true;
  }
  return false;
}

int RealismCommand(const RealismArgs& args) {
  if (const std::string problem = args.real.Check(); !problem.empty()) throw InputError("realism", problem);
  if (args.float_unit_flag != nullptr && args.float_unit_flag->count() > 0) {
    std::vector<std::string> skipped;
    const std::vector<std::string> files = ListRealFrames(args.real_dir, &skipped);
    if (std::none_of(files.begin(), files.end(), MayHoldFloats)) {
      throw InputError("--float-unit", "applies to float frames (.npy, 32-bit TIFF), and " + args.real_dir +
                                           " holds none: leave it out");
    }
  }
  CheckRealismFolder(args.output);  // a folder it may not use fails before the work
  const Dataset dataset = Dataset::Open(args.dataset, Verify::kOnRead, args.threads);
  PrintWarnings(dataset.warnings());
  FrameSet real = MeasureRealFrames(args.real_dir, args.real, args.static_sequence, args.threads);
  FrameSet synthetic = MeasureDatasetFrames(dataset, StridedFrames(dataset.num_frames(), args.stride), args.threads);
  const RealismComparison c = CompareFrameSets(std::move(synthetic), std::move(real));
  WriteRealismFolder(c, args.output);
  std::printf("views that are not blank: statistic, real median, synthetic median, synthetic / real\n");
  for (const StatisticRow& row : c.rows) {
    std::printf("  %-58s %10.3f %10.3f %8.2f\n", (row.label + (row.unit.empty() ? "" : ", " + row.unit)).c_str(),
                row.not_blank.real.median, row.not_blank.synthetic.median, row.not_blank.median_ratio);
  }
  const auto share = [](int part, int whole) { return whole > 0 ? 100.0 * part / whole : NAN; };
  std::printf("blank views: real %.1f %%, synthetic %.1f %%\n", share(c.real.Blank(), c.real.Radiometric()),
              share(c.synthetic.Blank(), c.synthetic.Radiometric()));
  if (c.real.Radiometric() < static_cast<int>(c.real.frames.size())) {
    std::printf("%zu real frames are 8-bit: no temperature statistics for those\n",
                c.real.frames.size() - static_cast<size_t>(c.real.Radiometric()));
  }
  std::printf("report: %s/realism.md\n", args.output.c_str());
  return 0;
}

}  // namespace

Command AddRealismCommand(CLI::App* app) {
  auto args = std::make_shared<RealismArgs>();
  CLI::App* cmd = app->add_subcommand(
      "realism",
      "compare a dataset's frames with a folder of real thermal frames: corners, edges, entropy, "
      "spectrum slope, flat-region noise, temperatures, wall residual, blank views, temporal noise");
  cmd->add_option("dataset", args->dataset, "dataset folder written by hoilcd render")->required();
  cmd->add_option("real_dir", args->real_dir,
                  "folder of real frames: 16-bit PNG/TIFF (with --scale and --offset), .npy (°C or K), "
                  "32-bit float TIFF, FLIR radiometric JPEG, other 8-bit PNG/JPEG (no temperature statistics)")
      ->required();
  cmd->add_option("-o,--output", args->output,
                  "folder for realism.json, realism.md and histograms/ (a new or empty folder, or an earlier "
                  "realism output)")
      ->type_name("DIR")
      ->required();
  cmd->add_option("--stride", args->stride, "use every N-th frame of the dataset")
      ->check(CLI::Range(1, kMaxFrames))
      ->capture_default_str();
  cmd->add_option("--scale", args->real.scale,
                  "16-bit frames: kelvin per count, T[°C] = value * scale + offset (centikelvin: 0.01)");
  cmd->add_option("--offset", args->real.offset_c, "16-bit frames: °C at count 0 (centikelvin: -273.15)");
  args->float_unit_flag = cmd->add_option("--float-unit", args->real.float_unit,
                                          "float frames (.npy, 32-bit TIFF): c, k, or auto (median above 150: kelvin)")
                              ->capture_default_str();
  cmd->add_flag("--static", args->static_sequence,
                "the real frames, in name order, are one static view: measure their temporal noise");
  AddThreadsFlag(cmd, &args->threads);
  return {cmd, [args] { return RealismCommand(*args); }};
}

}  // namespace hoilcd
