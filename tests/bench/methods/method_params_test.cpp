#include "hoilcd/bench/methods/method_params.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/sim/output/sequence.h"
#include "option_properties.h"
#include "test_dir.h"
#include "tiny_room.h"

namespace hoilcd {
namespace {

std::string ParamError(const std::string& param, const std::vector<std::string>& methods = {}) {
  try {
    CheckParams({param}, methods);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MethodParams, EveryBadParamIsAnErrorNamingItAndWhatWasExpected) {
  EXPECT_EQ(ParamError("slcd.ransac_trials=50"), "");
  EXPECT_EQ(ParamError("fusion.k=60"), "");
  EXPECT_EQ(ParamError("persons.threshold_c=27"), "");
  EXPECT_EQ(ParamError("keypoints.detector=orb"), "");
  EXPECT_NE(ParamError("ransac_trials=50").find("--param: 'ransac_trials=50': expected NAME=VALUE with NAME = <method"),
            std::string::npos);
  EXPECT_NE(ParamError("slcd.ransac_trials").find("'slcd.ransac_trials': expected NAME=VALUE"), std::string::npos);
  EXPECT_NE(ParamError("superglue.k=1").find("'superglue.k=1': expected NAME=VALUE with NAME = <method or front end>"
                                             ".<field>, the method or front end one of: slcd, dlcd"),
            std::string::npos);
  EXPECT_NE(ParamError("slcd.trials=5").find("'slcd.trials=5': expected an option name (one of: ransac_trials"),
            std::string::npos) << ParamError("slcd.trials=5");
  EXPECT_NE(ParamError("slcd.ransac_trials=many").find("'slcd.ransac_trials=many': expected a whole number"),
            std::string::npos) << ParamError("slcd.ransac_trials=many");
  EXPECT_NE(ParamError("slcd.ransac_trials=0").find("'slcd.ransac_trials=0': ransac_trials"), std::string::npos)
      << ParamError("slcd.ransac_trials=0");
  EXPECT_NE(ParamError("thumb.x=1").find("method thumb has no parameters"), std::string::npos);
  EXPECT_NE(ParamError("keypoints.detector=superpoint").find("'keypoints.detector=superpoint'"), std::string::npos);
  EXPECT_FALSE(FormatParams().empty());
}

TEST(MethodParams, EveryParamIsAFieldOfTheOptionsTablesWithItsDefaultUnitAndRange) {
  // Each --param is a view of a registered field (its struct's own table, reached through
  // BenchOptions'), never a second declaration: same kind, default, unit, range and description.
  const std::vector<OptionInfo> fields = BenchOptions::Table().List();
  std::vector<const OptionTable<BenchOptions>*> tables;
  for (const auto& m : RegisteredMethods()) {
    if (m->Params() != nullptr) tables.push_back(m->Params());
  }
  for (FrontEnd f : {FrontEnd::kKeypoints, FrontEnd::kPersons, FrontEnd::kThumbnails}) {
    tables.push_back(&FrontEndParams(f));
  }
  int params = 0;
  for (const OptionTable<BenchOptions>* table : tables) {
    for (const OptionInfo& p : table->List()) {
      ++params;
      const bool registered = std::any_of(fields.begin(), fields.end(), [&](const OptionInfo& f) {
        return f.kind == p.kind && f.default_json == p.default_json && f.unit == p.unit &&
               f.range.ToString() == p.range.ToString() && f.choices == p.choices && f.description == p.description;
      });
      EXPECT_TRUE(registered) << p.name << " is not a field of BenchOptions::Table()";
    }
  }
  EXPECT_GT(params, 20);
  const OptionInfo trials = RansacParams().List().front();
  EXPECT_EQ(trials.name, "ransac_trials");
  EXPECT_EQ(trials.default_json, "100");
  EXPECT_EQ(trials.range.ToString(), RansacOptions::Table().List().front().range.ToString());
}

TEST(BenchOptions, HoldTheirTablesDefaultsTheBenchsTrackingFilterAndEveryBoundIsChecked) {
  const BenchOptions options;
  EXPECT_EQ(options.tracking_metrics.min_visible_fraction, 0.2);  // the bench's own, not the library's 0
  EXPECT_EQ(options.tracking_metrics.min_box_height_px, 16);
  EXPECT_EQ(options.tracking_metrics.iou_threshold, TrackingMetricsOptions().iou_threshold);
  EXPECT_EQ(options.rrf_k, 0.0);
  EXPECT_EQ(options.ransac.trials, RansacOptions().trials);
  ExpectConstructedHoldsTheTableDefaults<BenchOptions>();
  EXPECT_GT(ExpectEveryBoundCrossedIsNamedByCheck<BenchOptions>(), 100);
  BenchOptions bad;
  bad.methods = {"superglue"};
  EXPECT_EQ(bad.Check(), "methods: unknown method 'superglue'");
}

TEST(MethodParams, AParamOfAMethodNotRunOrAFrontEndNoMethodUsesIsAnErrorNotIgnored) {
  EXPECT_EQ(ParamError("slcd.ransac_trials=50", {"slcd", "thumb"}), "");
  EXPECT_EQ(ParamError("keypoints.max_keypoints=500", {"slcd"}), "");
  EXPECT_EQ(ParamError("persons.threshold_c=27", {"dlcd"}), "");
  EXPECT_NE(ParamError("dlcd.ransac_trials=50", {"slcd", "thumb"})
                .find("--param: 'dlcd.ransac_trials=50': method dlcd is not run (methods: slcd, thumb); add it to "
                      "--methods or drop the parameter"),
            std::string::npos)
      << ParamError("dlcd.ransac_trials=50", {"slcd", "thumb"});
  EXPECT_NE(ParamError("persons.threshold_c=27", {"slcd", "thumb"})
                .find("'persons.threshold_c=27': front end persons is used by none of the methods run (methods: slcd, "
                      "thumb)"),
            std::string::npos)
      << ParamError("persons.threshold_c=27", {"slcd", "thumb"});
}

TEST(MethodParams, AParamChangesOnlyItsOwnMethodOrFrontEnd) {
  const test::TestDir temp;
  const Dataset dataset = test::TinyRoomDataset(temp / "dataset");
  BenchOptions options;
  options.methods = {"thumb", "thumb-seq"};
  const BenchResult plain = RunBench(dataset, options);
  options.params = {"thumb-seq.sequence_length=3"};
  const BenchResult seq = RunBench(dataset, options);
  EXPECT_EQ(seq.runs[0].scores, plain.runs[0].scores);  // thumb untouched
  EXPECT_NE(seq.runs[1].scores, plain.runs[1].scores);
  options.params = {"thumbnails.width_px=16", "thumbnails.height_px=12"};
  const BenchResult small = RunBench(dataset, options);
  EXPECT_NE(small.runs[0].scores, plain.runs[0].scores);  // the front end changed for both
  EXPECT_NE(small.runs[1].scores, plain.runs[1].scores);
  options.params = {"thumb-seq.sequence_length=0"};
  EXPECT_THROW(RunBench(dataset, options), InputError);
}

}  // namespace
}  // namespace hoilcd
