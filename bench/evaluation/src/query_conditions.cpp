#include "hoilcd/bench/evaluation/query_conditions.h"

#include <algorithm>
#include <map>
#include <set>

#include "hoilcd/bench/evaluation/json_number.h"
#include "hoilcd/core/dataset/exr_io.h"
#include "hoilcd/core/util/error.h"
#include "hoilcd/core/util/parallel.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {
namespace {

constexpr double kPi = 3.14159265358979323846;

double WrapRad(double a) { return std::remainder(a, 2 * kPi); }

// The EXR-based fields of one frame: person pixels, spread of the true temperature, whether only
// walls, floor and ceiling are in view, and the static pixels with contrast.
void AddImageConditions(const Dataset& dataset, int frame, QueryConditions* c) {
  const ExrChannels channels = ReadDatasetExr(dataset, frame);
  const std::string path = DatasetExrPath(dataset, frame);
  const cv::Mat& t = ExrChannel(channels, "T_true", path);
  const cv::Mat& cls = ExrChannel(channels, "class", path);
  const DatasetManifest& manifest = dataset.manifest();
  const int person = manifest.ClassId("person");
  const std::set<int> structure = {manifest.ClassId("wall"), manifest.ClassId("floor"), manifest.ClassId("ceiling")};
  std::vector<float> values;
  values.reserve(t.total());
  int person_pixels = 0, contrast = 0;
  bool structure_only = true;
  for (int y = 0; y < t.rows; ++y) {
    for (int x = 0; x < t.cols; ++x) {
      const int k = static_cast<int>(cls.at<float>(y, x));
      const float v = t.at<float>(y, x);
      values.push_back(v);
      if (k == person) {
        ++person_pixels;
        structure_only = false;
        continue;
      }
      if (!structure.count(k)) structure_only = false;
      const bool right = x + 1 < t.cols && static_cast<int>(cls.at<float>(y, x + 1)) != person &&
                         std::abs(t.at<float>(y, x + 1) - v) >= kContrastK;
      const bool down = y + 1 < t.rows && static_cast<int>(cls.at<float>(y + 1, x)) != person &&
                        std::abs(t.at<float>(y + 1, x) - v) >= kContrastK;
      contrast += right || down;
    }
  }
  const auto percentile = [&](double q) {
    const size_t at = static_cast<size_t>(q * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(at), values.end());
    return static_cast<double>(values[at]);
  };
  c->person_pixels = person_pixels;
  c->temperature_spread_k = values.empty() ? NAN : percentile(0.98) - percentile(0.02);
  c->structure_only_classes = structure_only;
  c->structure_contrast_pixels = contrast;
  c->structure_contrast_fraction = static_cast<double>(contrast) / static_cast<double>(t.total());
  c->blank = structure_only && c->temperature_spread_k < kBlankSpreadK;
}

// Turn rate, lap and the nearest true match, from the true poses. The turn rate is over the frames
// beside the query in its own recording run (the next run starts hours later, at the dock).
void AddPoseConditions(const std::vector<PoseRecord>& poses, const Query& q, QueryConditions* c) {
  const int n = static_cast<int>(poses.size());
  int a = std::max(0, q.frame - 1), b = std::min(n - 1, q.frame + 1);
  if (poses[a].run != poses[q.frame].run) a = q.frame;
  if (poses[b].run != poses[q.frame].run) b = q.frame;
  if (b > a && poses[b].time_s > poses[a].time_s) {
    c->turn_rate_deg_s =
        std::abs(WrapRad(poses[b].theta_rad - poses[a].theta_rad)) * 180 / kPi / (poses[b].time_s - poses[a].time_s);
  }
  const PoseRecord& p = poses[q.frame];
  for (size_t j = 0; j < q.database.size(); ++j) {
    if (!q.is_true_match[j]) continue;
    const PoseRecord& r = poses[q.database[j]];
    const double d = std::hypot(r.x_m - p.x_m, r.y_m - p.y_m);
    if (std::isnan(c->nearest_true_distance_m) || d < c->nearest_true_distance_m) {
      c->nearest_true_distance_m = d;
      c->nearest_true_heading_deg = std::abs(WrapRad(r.theta_rad - p.theta_rad)) * 180 / kPi;
    }
  }
}

}  // namespace

QueryConditions ImageConditionsOf(const Dataset& dataset, int frame) {
  QueryConditions c;
  c.frame = frame;
  AddImageConditions(dataset, frame, &c);
  return c;
}

std::vector<QueryConditions> ComputeQueryConditions(const Dataset& dataset, const std::vector<Query>& queries,
                                                    int threads) {
  const bool has_persons = dataset.manifest().outputs.persons;
  const bool has_exr = dataset.manifest().outputs.exr;
  std::set<int> ffc_or_frozen;
  for (const DatasetEvent& e : dataset.events())
    if (e.type == "ffc" || e.type == "freeze") ffc_or_frozen.insert(e.frame);
  std::vector<QueryConditions> out(queries.size());
  ParallelFor(static_cast<int64_t>(queries.size()), threads, [&](int64_t i) {
    const Query& q = queries[i];
    QueryConditions& c = out[i];
    c.frame = q.frame;
    c.lap = q.lap;
    c.ffc_or_frozen = ffc_or_frozen.count(q.frame) > 0;
    if (has_persons) {
      double occlusion = 0;
      const FramePersons& frame = dataset.persons().at(static_cast<size_t>(q.frame));
      HOILCD_CHECK_MSG(frame.frame == q.frame, "persons.json is not indexed by frame");
      for (const PersonRecord& p : frame.persons) {
        if (p.visible_fraction <= 0) continue;
        ++c.people_in_view;
        c.walkers_in_view += !p.seated;
        occlusion += p.occlusion_fraction;
      }
      if (c.people_in_view > 0) c.mean_occlusion = occlusion / c.people_in_view;
    }
    if (has_exr) AddImageConditions(dataset, q.frame, &c);
    AddPoseConditions(dataset.poses(), q, &c);
  });
  return out;
}

std::string ConditionsCsvHeader() {
  return ",people_in_view,walkers_in_view,mean_occlusion,person_pixels,temperature_spread_k,blank_view,"
         "structure_contrast_pixels,structure_contrast_fraction,ffc_or_frozen,turn_rate_deg_s,nearest_true_distance_m,"
         "nearest_true_heading_deg";
}

std::string ConditionsCsvRow(const QueryConditions& c) {
  const bool exr = c.person_pixels >= 0;
  return "," + std::to_string(c.people_in_view) + "," + std::to_string(c.walkers_in_view) + "," +
         CsvNumber(c.mean_occlusion, 6) + "," + (exr ? std::to_string(c.person_pixels) : "") + "," +
         CsvNumber(c.temperature_spread_k, 6) + "," + (exr ? (c.blank ? "1" : "0") : "") + "," +
         (exr ? std::to_string(c.structure_contrast_pixels) : "") + "," + CsvNumber(c.structure_contrast_fraction, 6) +
         "," + (c.ffc_or_frozen ? "1" : "0") + "," + CsvNumber(c.turn_rate_deg_s, 6) + "," +
         CsvNumber(c.nearest_true_distance_m, 6) + "," + CsvNumber(c.nearest_true_heading_deg, 6);
}

std::vector<std::string> StratificationNames() {
  return {"view", "contrast", "occlusion", "walkers", "turning", "lap", "ffc"};
}
std::vector<std::string> DefaultStratifications() { return {"view", "contrast", "occlusion", "walkers"}; }

namespace {

// Each stratification's strata in report order; "lap" has one per lap, named "lap N".
const std::vector<std::string>& NamedStrata(const std::string& stratification) {
  static const std::map<std::string, std::vector<std::string>> strata = {
      {"view", {"blank view", "static structure only", "no people", "1-2 people", "3 or more people"}},
      {"contrast", {"static contrast < 1 % of pixels", "static contrast 1-4 %", "static contrast >= 4 %"}},
      {"occlusion", {"people < 25 % occluded", "people 25-50 % occluded", "people >= 50 % occluded"}},
      {"walkers", {"no walker in view", "walker in view"}},
      {"turning", {"straight (< 10 deg/s)", "turning (>= 10 deg/s)"}},
      {"lap", {}},
      {"ffc", {"live frame", "FFC or frozen frame"}}};
  const auto it = strata.find(stratification);
  HOILCD_CHECK_MSG(it != strata.end(), "unknown stratification " << stratification);
  return it->second;
}

// The position of `c`'s stratum in its stratification's order (-1: in none, e.g. occlusion with
// nobody in view); for "lap", the lap.
int StratumIndex(const std::string& stratification, const QueryConditions& c) {
  NamedStrata(stratification);  // checks the name
  if (stratification == "view") {
    if (c.people_in_view >= 3) return 4;
    if (c.people_in_view >= 1) return 3;
    if (c.person_pixels < 0) return 2;  // no EXR: blank views cannot be told apart
    return c.blank ? 0 : 1;
  }
  if (stratification == "contrast") {
    if (std::isnan(c.structure_contrast_fraction)) return -1;  // no EXR
    return c.structure_contrast_fraction < 0.01 ? 0 : c.structure_contrast_fraction < 0.04 ? 1 : 2;
  }
  if (stratification == "occlusion") {
    if (c.people_in_view == 0) return -1;
    return c.mean_occlusion < 0.25 ? 0 : c.mean_occlusion < 0.5 ? 1 : 2;
  }
  if (stratification == "walkers") return c.walkers_in_view > 0 ? 1 : 0;
  if (stratification == "turning") return std::isnan(c.turn_rate_deg_s) ? -1 : c.turn_rate_deg_s >= 10 ? 1 : 0;
  if (stratification == "lap") return c.lap;
  return c.ffc_or_frozen ? 1 : 0;  // ffc
}

std::string StratumName(const std::string& stratification, int index) {
  if (stratification == "lap") return "lap " + std::to_string(index + 1);
  return NamedStrata(stratification).at(static_cast<size_t>(index));
}

}  // namespace

std::string StratumOf(const std::string& stratification, const QueryConditions& c) {
  const int index = StratumIndex(stratification, c);
  return index < 0 ? "" : StratumName(stratification, index);
}

double ChanceReciprocalRank(int database_size, int true_matches) {
  if (true_matches <= 0 || database_size < true_matches) return NAN;
  // P(first true at k) = (t / (D - k + 1)) * prod_{i<k} (D - t - i + 1) / (D - i + 1).
  double none_before = 1, expected = 0;
  const double d = database_size, t = true_matches;
  for (int k = 1; k <= database_size - true_matches + 1; ++k) {
    const double here = t / (d - k + 1);
    expected += none_before * here / k;
    none_before *= 1 - here;
  }
  return expected;
}

std::vector<StratumRow> Stratify(const std::vector<QueryConditions>& conditions, const std::vector<std::string>& names,
                                 const std::vector<const std::vector<QueryRecord>*>& records,
                                 const std::vector<std::string>& stratifications) {
  std::vector<StratumRow> rows;
  for (const std::string& s : stratifications) {
    std::map<int, std::vector<size_t>> members;  // by stratum index: report order
    for (size_t i = 0; i < conditions.size(); ++i) {
      const int index = StratumIndex(s, conditions[i]);
      if (index >= 0) members[index].push_back(i);
    }
    for (const auto& [index, queries] : members) {
      StratumRow row;
      row.stratification = s;
      row.stratum = StratumName(s, index);
      row.methods = names;
      double chance = 0;
      for (size_t m = 0; m < records.size(); ++m) {
        std::vector<QueryRecord> subset;
        for (size_t i : queries) subset.push_back((*records[m])[i]);
        const MethodMetrics metrics = SummariseQueries(std::move(subset));
        row.mrr.push_back(metrics.mrr);
        row.recall_at_1.push_back(metrics.recall_at_1);
        row.queries = metrics.queries_scored;
      }
      if (!records.empty()) {
        for (size_t i : queries) {
          const QueryRecord& r = (*records[0])[i];
          if (r.scored) chance += ChanceReciprocalRank(r.database_size, r.true_matches);
        }
      }
      row.chance_mrr = row.queries > 0 ? chance / row.queries : NAN;
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

nlohmann::json StrataJson(const std::vector<StratumRow>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const StratumRow& r : rows) {
    nlohmann::json methods;
    for (size_t m = 0; m < r.methods.size(); ++m) {
      methods[r.methods[m]] = {{"mrr", JsonNumber(r.mrr[m])}, {"recall_at_1", JsonNumber(r.recall_at_1[m])}};
    }
    out.push_back({{"stratification", r.stratification},
                   {"stratum", r.stratum},
                   {"queries", r.queries},
                   {"chance_mrr", JsonNumber(r.chance_mrr)},
                   {"methods", methods}});
  }
  return out;
}

}  // namespace hoilcd
