#include "hoilcd/bench/report/gallery.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "hoilcd/bench/methods/method_params.h"
#include "hoilcd/bench/methods/methods.h"
#include "hoilcd/bench/report/gallery_sample.h"
#include "hoilcd/bench/report/html.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {
namespace {

constexpr int kJpegQuality = 85;  // frames in the page: ~10 KB each, the thermal texture intact
constexpr int kPairGapPx = 4;     // between the two frames of a pair picture

// The frame as the report's figures show it (inferno colour map), as a JPEG data URI.
std::string FrameUri(const Dataset& dataset, int frame) {
  cv::Mat colour;
  cv::applyColorMap(dataset.Thermal(frame), colour, cv::COLORMAP_INFERNO);
  std::vector<uchar> jpeg;
  cv::imencode(".jpg", colour, jpeg, {cv::IMWRITE_JPEG_QUALITY, kJpegQuality});
  return DataUri("image/jpeg", std::string_view(reinterpret_cast<const char*>(jpeg.data()), jpeg.size()));
}

// Every frame the entries use, once, in a hidden SVG the tiles reference (<use href="#frame-N">).
std::string FrameDefs(const Dataset& dataset, const std::set<int>& frames, int width, int height) {
  std::string html = "<svg width=\"0\" height=\"0\" style=\"position:absolute\" aria-hidden=\"true\"><defs>\n";
  for (int f : frames) {
    html += "<image id=\"frame-" + std::to_string(f) + "\" width=\"" + std::to_string(width) + "\" height=\"" +
            std::to_string(height) + "\" href=\"" + FrameUri(dataset, f) + "\"/>\n";
  }
  return html + "</defs></svg>\n";
}

// A pixel coordinate in the page, to a tenth of a pixel.
std::string Coord(double v) { return Fixed(v, 1); }

// Each frame's features once, as a path of round dots the tiles reference (<use href="#kp-N">,
// "#hoi-N", and the oracles' "#ikp-N" and "#thoi-N"): a frame's keypoints are drawn in every entry
// that shows it, for every method on them, and a path of "M x y h0" dots is a third of the size of
// circles.
std::string FeatureId(ShownFeatures kind, int frame) {
  const char* prefix = "kp-";
  if (kind == ShownFeatures::kHoiPoints) prefix = "hoi-";
  if (kind == ShownFeatures::kIdealKeypoints) prefix = "ikp-";
  if (kind == ShownFeatures::kTrueHoiPoints) prefix = "thoi-";
  return prefix + std::to_string(frame);
}

// A line's path data between two pixel centres, the second shifted right by dx.
std::string Segment(const Point2& a, const Point2& b, double dx) {
  return "M" + Coord(a.x + 0.5) + " " + Coord(a.y + 0.5) + "L" + Coord(b.x + 0.5 + dx) + " " + Coord(b.y + 0.5);
}

// A method's features of one frame (null when it shows none or none were kept).
const FrameFeatures* FeaturesOf(const GalleryInput& in, const LoopClosureMethod* method, int frame) {
  if (method == nullptr || method->Features() == ShownFeatures::kNone || in.features == nullptr || frame < 0 ||
      frame >= static_cast<int>(in.features->size()))
    return nullptr;
  return &(*in.features)[frame];
}

// Why a method's tile draws no matches, in plain words for its caption.
std::string NoMatchesNote(const GalleryInput& in, const LoopClosureMethod* method, int top1) {
  if (method == nullptr) return "scored outside hoilcd: no points to draw";
  if (method->Features() == ShownFeatures::kNone) {
    if (method->Inputs().empty()) return "matches no keypoints or HOI points: nothing to draw";
    std::string inputs;
    for (const std::string& name : method->Inputs()) inputs += (inputs.empty() ? "" : ", ") + name;
    return "fuses the rankings of " + inputs + ": no point matches of its own";
  }
  if (in.features == nullptr) return "its features are not in this report: no points to draw";
  if (top1 < 0) return "no top-1 to match";
  return "gives no matches for the gallery (no MatchPair): its features alone";
}

// One method as the gallery draws it: the registered method (null: scored outside hoilcd) and its
// own options as it ran.
struct DrawnMethod {
  const GalleryMethod* shown;
  const LoopClosureMethod* method = nullptr;
  std::unique_ptr<MethodOptions> own;
};

// The query and the method's top-1 side by side: features, matches (red) and RANSAC inliers (green).
std::string PairTile(const GalleryInput& in, const DrawnMethod& m, size_t q, int width, int height,
                     std::set<std::pair<ShownFeatures, int>>* drawn_features) {
  const Query& query = in.queries[q];
  const QueryRecord& rec = (*m.shown->records)[q];
  const int top1 = rec.top1_frame;
  const int dx = width + kPairGapPx;
  const FrameFeatures *qf = FeaturesOf(in, m.method, query.frame), *rf = FeaturesOf(in, m.method, top1);
  const ShownFeatures shown = m.method != nullptr ? m.method->Features() : ShownFeatures::kNone;
  const std::vector<Point2> qp = qf ? qf->Points(shown) : std::vector<Point2>();
  const std::vector<Point2> rp = rf ? rf->Points(shown) : std::vector<Point2>();
  std::optional<PairMatches> matches;
  if (qf != nullptr && rf != nullptr) {
    matches = m.method->MatchPair(
        {m.own.get(), qp, rp, qf->Hoi(shown), rf->Hoi(shown), query.frame, top1, height, in.dataset.manifest().seed});
  }
  const std::string outcome = GalleryOutcome(rec);
  std::string svg = "<svg viewBox=\"0 0 " + std::to_string(width + dx) + " " + std::to_string(height) +
                    "\"><use href=\"#frame-" + std::to_string(query.frame) + "\"/>";
  if (top1 >= 0) svg += "<use href=\"#frame-" + std::to_string(top1) + "\" x=\"" + std::to_string(dx) + "\"/>";
  if (!qp.empty()) {
    svg += "<use href=\"#" + FeatureId(shown, query.frame) + "\"/>";
    drawn_features->insert({shown, query.frame});
  }
  if (!rp.empty()) {
    svg += "<use href=\"#" + FeatureId(shown, top1) + "\" x=\"" + std::to_string(dx) + "\"/>";
    drawn_features->insert({shown, top1});
  }
  std::string caption = EscapeHtml(m.shown->name) + " top-1 " + (top1 >= 0 ? std::to_string(top1) : "none") +
                        ": <b class=\"" + outcome + "\">" + outcome + "</b>, score " + Fixed(rec.top1_score, 2) +
                        (rec.top1_tie_size > 1 ? " (" + std::to_string(rec.top1_tie_size) + " tied)" : "") +
                        ", first true match at rank " + Fixed(rec.first_true_rank, 1);
  if (matches) {
    for (bool inliers : {false, true}) {  // inliers drawn last, on top
      std::string d;
      for (size_t k = 0; k < matches->matches.size(); ++k) {
        if ((matches->inlier[k] != 0) != inliers) continue;
        d += Segment(qp[matches->matches[k].query], rp[matches->matches[k].reference], dx);
      }
      if (d.empty()) continue;
      svg += std::string(inliers ? "<path class=\"inlier\" stroke=\"#3f3\" stroke-width=\"0.9\""
                                 : "<path class=\"outlier\" stroke=\"#f44\" stroke-width=\"0.6\" opacity=\"0.7\"") +
             " d=\"" + d + "\"/>";
    }
    caption += "; " + std::to_string(matches->matches.size()) + " matches, <span class=\"inliers\">" +
               std::to_string(matches->inliers) + "</span> RANSAC inliers";
  } else {
    caption += "; <span class=\"no-matches\">" + EscapeHtml(NoMatchesNote(in, m.method, top1)) + "</span>";
  }
  return "<figure class=\"tile pair\" data-method=\"" + EscapeHtml(m.shown->name) + "\">" + svg + "</svg><figcaption>" +
         caption + "</figcaption></figure>";
}

// A single frame with a caption.
std::string FrameTile(int frame, const std::string& caption_html, int width, int height) {
  return "<figure class=\"tile\"><svg viewBox=\"0 0 " + std::to_string(width) + " " + std::to_string(height) +
         "\"><use href=\"#frame-" + std::to_string(frame) + "\"/></svg><figcaption>" + caption_html +
         "</figcaption></figure>";
}

// The true match nearest the query's true position (ties: the earlier frame); -1 when none.
int NearestTrueMatch(const Dataset& dataset, const Query& query) {
  const std::vector<PoseRecord>& poses = dataset.poses();
  int best = -1;
  double best_d = INFINITY;
  for (size_t j = 0; j < query.database.size(); ++j) {
    if (!query.is_true_match[j]) continue;
    const PoseRecord &a = poses[query.frame], &b = poses[query.database[j]];
    const double d = std::hypot(a.x_m - b.x_m, a.y_m - b.y_m);
    if (d < best_d) best_d = d, best = query.database[j];
  }
  return best;
}

// The query's conditions in one line (the fields of queries.csv), its strata after.
std::string ConditionsLine(const QueryConditions& c, const std::vector<std::string>& strata) {
  std::string line = "people in view " + std::to_string(c.people_in_view) + " (walkers " +
                     std::to_string(c.walkers_in_view) + "), mean occlusion " + Fixed(c.mean_occlusion, 2);
  if (c.person_pixels >= 0) {
    line += ", person pixels " + std::to_string(c.person_pixels) + ", temperature spread " +
            Fixed(c.temperature_spread_k, 2) + " K, structure contrast " +
            Fixed(100 * c.structure_contrast_fraction, 1) + " %" + (c.blank ? ", blank view" : "");
  }
  line += std::string(c.ffc_or_frozen ? ", FFC or frozen frame" : "") + ", turning " + Fixed(c.turn_rate_deg_s, 1) +
          " deg/s, nearest true match " + Fixed(c.nearest_true_distance_m, 2) + " m / " +
          Fixed(c.nearest_true_heading_deg, 1) + " deg";
  std::string shown;
  for (const std::string& s : strata) shown += (shown.empty() ? "" : "; ") + s;
  return EscapeHtml(line) + (shown.empty() ? "" : "<br>strata: " + EscapeHtml(shown));
}

std::string Entry(const GalleryInput& in, const std::vector<DrawnMethod>& methods, size_t q, int width, int height,
                  std::set<std::pair<ShownFeatures, int>>* drawn_features) {
  const Query& query = in.queries[q];
  const QueryConditions& c = in.conditions[q];
  std::vector<std::string> strata, outcomes;
  for (const std::string& s : in.stratifications) {
    const std::string stratum = StratumOf(s, c);
    if (!stratum.empty()) strata.push_back(s + ": " + stratum);
  }
  for (const DrawnMethod& m : methods) outcomes.push_back(m.shown->name + ":" + GalleryOutcome((*m.shown->records)[q]));
  const auto joined = [](const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& i : items) out += (out.empty() ? "" : "|") + i;
    return EscapeHtml(out);
  };
  const int truth = NearestTrueMatch(in.dataset, query);
  std::string html = "<div class=\"entry\" data-query=\"" + std::to_string(query.frame) + "\" data-outcomes=\"" +
                     joined(outcomes) + "\" data-strata=\"" + joined(strata) + "\" data-blank=\"" +
                     (c.blank ? "1" : "0") + "\">\n<h4>query " + std::to_string(query.frame) + " (t " +
                     Fixed(in.dataset.poses()[query.frame].time_s, 2) + " s, lap " + std::to_string(query.lap + 1) +
                     ", " + std::to_string(query.NumTrueMatches()) + " true matches of " +
                     std::to_string(query.database.size()) + ")</h4>\n<p class=\"conditions\">" +
                     ConditionsLine(c, strata) + "</p>\n<div class=\"tiles\">";
  html += FrameTile(query.frame, "query " + std::to_string(query.frame), width, height);
  if (truth >= 0) html += FrameTile(truth, "true match " + std::to_string(truth) + " (the nearest)", width, height);
  for (const DrawnMethod& m : methods) html += PairTile(in, m, q, width, height, drawn_features);
  return html + "</div></div>\n";
}

// The features the tiles use (FeatureId), each frame's once, in a hidden SVG.
std::string FeatureDefs(const GalleryInput& in, const std::set<std::pair<ShownFeatures, int>>& used) {
  std::string html = "<svg width=\"0\" height=\"0\" style=\"position:absolute\" aria-hidden=\"true\"><defs>\n";
  for (const auto& [kind, frame] : used) {
    std::string d;
    for (const Point2& p : (*in.features)[frame].Points(kind))
      d += "M" + Coord(p.x + 0.5) + " " + Coord(p.y + 0.5) + "h0";
    html += "<path id=\"" + FeatureId(kind, frame) +
            "\" stroke=\"#4cf\" stroke-width=\"3.5\" stroke-linecap=\"round\" d=\"" + d + "\"/>\n";
  }
  return html + "</defs></svg>\n";
}

// The selects of the gallery's filters (the script in html.cpp reads their ids).
std::string Filters(const std::vector<DrawnMethod>& methods, const std::vector<std::string>& strata) {
  std::string html =
      "<div class=\"filters\"><label>method <select id=\"gallery-method\"><option value=\"*\">any</option>";
  for (const DrawnMethod& m : methods) html += "<option>" + EscapeHtml(m.shown->name) + "</option>";
  html += "</select></label><label>stratum <select id=\"gallery-stratum\"><option value=\"*\">any</option>";
  for (const std::string& s : strata) html += "<option>" + EscapeHtml(s) + "</option>";
  return html +
         "</select></label><label>outcome <select id=\"gallery-outcome\"><option value=\"*\">any</option>"
         "<option value=\"hit\">hit</option><option value=\"miss\">miss</option>"
         "<option value=\"blank\">blank view</option></select></label><span id=\"gallery-shown\"></span></div>\n";
}

}  // namespace

Gallery MakeGallery(const GalleryInput& in) {
  Gallery gallery;
  std::vector<const std::vector<QueryRecord>*> records;
  std::vector<DrawnMethod> methods;
  for (const GalleryMethod& m : in.methods) {
    records.push_back(m.records);
    DrawnMethod drawn{&m, nullptr, nullptr};
    if (IsMethod(m.name)) {
      drawn.method = &FindMethod(m.name);
      drawn.own = OptionsWithParams(*drawn.method, in.params);
    }
    methods.push_back(std::move(drawn));
  }
  gallery.sampled = SampleGallery(records, in.conditions, in.stratifications, in.sampling);
  const int width = in.dataset.manifest().intrinsics.width, height = in.dataset.manifest().intrinsics.height;
  std::set<int> frames;
  std::vector<std::string> strata;
  for (size_t q : gallery.sampled) {
    frames.insert(in.queries[q].frame);
    const int truth = NearestTrueMatch(in.dataset, in.queries[q]);
    if (truth >= 0) frames.insert(truth);
    for (const GalleryMethod& m : in.methods)
      if ((*m.records)[q].top1_frame >= 0) frames.insert((*m.records)[q].top1_frame);
    for (const std::string& s : in.stratifications) {
      const std::string stratum = StratumOf(s, in.conditions[q]);
      const std::string label = s + ": " + stratum;
      if (!stratum.empty() && std::find(strata.begin(), strata.end(), label) == strata.end()) strata.push_back(label);
    }
  }
  std::string pointless;  // the methods that match no points
  for (const DrawnMethod& m : methods) {
    if (m.method == nullptr || m.method->Features() == ShownFeatures::kNone)
      pointless += (pointless.empty() ? "" : ", ") + m.shown->name;
  }
  if (!pointless.empty()) {
    pointless = " The tiles of " + EscapeHtml(pointless) +
                " show the two frames alone: these methods match no "
                "keypoints or HOI points (each tile says why).";
  }
  std::string& html = gallery.html;
  html = "<h2 id=\"gallery-section\">Gallery of queries</h2>\n<p class=\"note\">" +
         std::to_string(gallery.sampled.size()) + " of " + std::to_string(in.queries.size()) +
         " queries: for every method, outcome (hit: its top-1 is a true "
         "match; miss) and stratum (and blank views), up to " +
         std::to_string(in.sampling.per_group) + " scored queries spread in time, no two within " +
         std::to_string(in.sampling.min_gap_frames) +
         " frames of each other. Each shows the query, its true match nearest in position, and every method's "
         "top-1 beside the query." +
         pointless +
         "</p>\n"
         "<p class=\"legend note\"><span style=\"color:#08a\">&#9679; features the method matches</span>"
         "<span style=\"color:#1a1\">&#9472; RANSAC inlier</span><span style=\"color:#d22\">&#9472; match RANSAC "
         "rejects</span></p>\n" +
         Filters(methods, strata) + FrameDefs(in.dataset, frames, width, height);
  std::set<std::pair<ShownFeatures, int>> drawn_features;
  std::string entries;
  for (size_t q : gallery.sampled) entries += Entry(in, methods, q, width, height, &drawn_features);
  html += FeatureDefs(in, drawn_features) + "<div id=\"gallery\">\n" + entries + "</div>\n";
  return gallery;
}

}  // namespace hoilcd
