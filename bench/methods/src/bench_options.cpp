#include "hoilcd/bench/methods/bench_options.h"

#include <algorithm>

#include "hoilcd/bench/methods/method_params.h"
#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/core/util/error.h"

namespace hoilcd {

BenchOptions::BenchOptions() { Table().FillDefaults(this); }

const OptionTable<BenchOptions>& BenchOptions::Table() {
  using O = BenchOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Nest("protocol", &O::protocol, ProtocolOptions::Table())
          .Nest("bootstrap", &O::bootstrap, BootstrapOptions::Table())
          .Nest("keypoints", &O::keypoints, KeypointOptions::Table())
          .Nest("detector", &O::detector, PersonDetectorOptions::Table())
          .Nest("tracker", &O::tracker, ByteTrackOptions::Table())
          .Nest("hoi", &O::hoi, HoiOptions::Table())
          .Nest("thumbnail", &O::thumbnail, ThumbnailOptions::Table())
          .Nest("tracking_metrics", &O::tracking_metrics,
                TrackingMetricsOptions::Table()
                    .WithDefault("min_visible_fraction", 0.2)
                    .WithDefault("min_box_height_px", 16))
          .Add("threads", &O::threads, 0, "", R::Any().AtLeast(0), "threads (0: every core)")
          .Add("slam", &O::slam, false, "run the SLAM back end over every method's loops (slam_run.h)")
          .Nest("slam_options", &O::slam_options, SlamRunOptions::Table())
          .Rule("methods",
                [](const O& o) {
                  for (const std::string& m : o.methods) {
                    if (!IsMethod(m)) return "unknown method '" + m + "'";
                  }
                  return std::string();
                })
          .Rule("strata",
                [](const O& o) {
                  const std::vector<std::string> known = StratificationNames();
                  for (const std::string& s : o.strata) {
                    if (std::find(known.begin(), known.end(), s) == known.end()) {
                      std::string list;
                      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
                      return "unknown stratification '" + s + "' (known: " + list + ")";
                    }
                  }
                  return std::string();
                })
          .Rule("params", [](const O& o) {
            try {
              CheckParams(o.params, o.methods);
            } catch (const InputError& e) {
              return e.problems().front().message;
            }
            return std::string();
          });
  return table;
}

std::string BenchOptions::Check() const { return Table().FirstProblem(*this); }

}  // namespace hoilcd
