#include "hoilcd/bench/methods/method_params.h"

#include <algorithm>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/bench/runner/runner.h"
#include "hoilcd/core/matching/track_aware_matching.h"
#include "hoilcd/core/place_recognition/temporal_consistency.h"
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
  EXPECT_NE(ParamError("superglue.k=1")
                .find("'superglue.k=1': expected NAME=VALUE with NAME = <method or front end>"
                      ".<field>, the method or front end one of: slcd, dlcd"),
            std::string::npos);
  EXPECT_NE(ParamError("slcd.trials=5").find("'slcd.trials=5': expected an option name (one of: ransac_trials"),
            std::string::npos)
      << ParamError("slcd.trials=5");
  EXPECT_NE(ParamError("slcd.ransac_trials=many").find("'slcd.ransac_trials=many': expected a whole number"),
            std::string::npos)
      << ParamError("slcd.ransac_trials=many");
  EXPECT_NE(ParamError("slcd.ransac_trials=0").find("'slcd.ransac_trials=0': ransac_trials"), std::string::npos)
      << ParamError("slcd.ransac_trials=0");
  EXPECT_NE(ParamError("thumb.x=1").find("method thumb has no parameters"), std::string::npos);
  // Every message is the parameter and what was expected, said once (issue 32 case 18).
  EXPECT_EQ(ParamError("thumbnails.=1"), "--param: 'thumbnails.=1': expected NAME=VALUE");
  EXPECT_NE(ParamError("fusion.k.x=1").find("'fusion.k.x=1': expected no field after 'k'"), std::string::npos)
      << ParamError("fusion.k.x=1");
  EXPECT_NE(ParamError("keypoints.detector=superpoint").find("'keypoints.detector=superpoint'"), std::string::npos);
  EXPECT_FALSE(FormatParams().empty());
}

TEST(MethodParams, EveryParamIsAFieldOfTheOptionsTablesWithItsDefaultUnitAndRange) {
  // Each --param is a view of a registered field (its struct's own table), never a second
  // declaration: same kind, default, unit, range and description. Fusion's k is its own field.
  std::vector<OptionInfo> fields = BenchOptions::Table().List();
  for (const std::vector<OptionInfo>& more :
       {RansacOptions::Table().List(), MatchOptions::Table().List(), TrackAwareOptions::Table().List(),
        SeqSlamOptions::Table().List(), TemporalConsistencyOptions::Table().List()}) {
    fields.insert(fields.end(), more.begin(), more.end());
  }
  std::vector<std::pair<std::string, std::vector<OptionInfo>>> tables;
  for (const auto& m : RegisteredMethods()) {
    if (const auto own = m->Options()) tables.emplace_back(m->Name(), own->List());
  }
  for (FrontEnd f : {FrontEnd::kKeypoints, FrontEnd::kPersons, FrontEnd::kThumbnails}) {
    tables.emplace_back(FrontEndName(f), FrontEndParams(f).List());
  }
  int params = 0;
  for (const auto& [scope, list] : tables) {
    for (const OptionInfo& p : list) {
      ++params;
      const bool registered = std::any_of(fields.begin(), fields.end(), [&](const OptionInfo& f) {
        return f.kind == p.kind && f.unit == p.unit && f.range.ToString() == p.range.ToString() &&
               f.choices == p.choices && f.description == p.description &&
               (f.default_json == p.default_json || p.name == "lo_refits");  // -lo: 2 refits, a view's default
      });
      EXPECT_TRUE(registered || (scope == "fusion" && p.name == "k")) << scope << "." << p.name;
    }
  }
  EXPECT_GT(params, 20);
  const OptionInfo trials = RansacParams().List().front();
  EXPECT_EQ(trials.name, "ransac_trials");
  EXPECT_EQ(trials.default_json, "100");
  EXPECT_EQ(trials.range.ToString(), RansacOptions::Table().List().front().range.ToString());
}

TEST(MethodParams, EveryMethodsOptionsAreSetCheckedAndReadBackThroughItsParams) {
  for (const auto& m : RegisteredMethods()) {
    const std::unique_ptr<MethodOptions> defaults = m->Options();
    if (defaults == nullptr) continue;
    const nlohmann::json at_default = defaults->ToJson();
    for (const OptionInfo& field : defaults->List()) {
      EXPECT_EQ(at_default[field.name].dump(), nlohmann::json::parse(field.default_json).dump())
          << m->Name() << "." << field.name;
      if (field.kind != OptionInfo::Kind::kNumber && field.kind != OptionInfo::Kind::kInteger) continue;
      // A value inside the range other than the default reaches the method's options, and no other's.
      const double base = std::stod(field.default_json);
      const double value = field.kind == OptionInfo::Kind::kInteger ? base + 1 : (base == 0 ? 0.5 : base / 2);
      const std::string param =
          m->Name() + "." + field.name + "=" +
          (field.kind == OptionInfo::Kind::kInteger ? std::to_string(static_cast<long long>(value))
                                                    : std::to_string(value));
      if (!field.range.Contains(value)) continue;
      EXPECT_EQ(ParamError(param, {m->Name()}), "") << param;
      const auto set = OptionsWithParams(*m, {param, "other.x=1"});
      EXPECT_EQ(set->ToJson()[field.name].get<double>(), value) << param;
    }
  }
}

TEST(BenchOptions, HoldTheirTablesDefaultsTheBenchsTrackingFilterAndEveryBoundIsChecked) {
  const BenchOptions options;
  EXPECT_EQ(options.tracking_metrics.min_visible_fraction, 0.2);  // the bench's own, not the library's 0
  EXPECT_EQ(options.tracking_metrics.min_box_height_px, 16);
  EXPECT_EQ(options.tracking_metrics.iou_threshold, TrackingMetricsOptions().iou_threshold);
  ExpectConstructedHoldsTheTableDefaults<BenchOptions>();
  EXPECT_GT(ExpectEveryBoundCrossedIsNamedByCheck<BenchOptions>(), 80);
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
