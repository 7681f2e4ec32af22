#include <algorithm>
#include <cmath>
#include <cstdio>

#include "hoilcd/bench/report/chart.h"
#include "hoilcd/bench/report/html.h"
#include "hoilcd/bench/report/html_report.h"
#include "hoilcd/core/util/text.h"

namespace hoilcd {
namespace {

constexpr double kSvgWidthPx = 900;  // the plot's width; the height follows the room's aspect
constexpr double kMarginPx = 10;

std::string Hex(const cv::Scalar& bgr) {
  char text[8];
  std::snprintf(text, sizeof(text), "#%02x%02x%02x", static_cast<int>(bgr[2]), static_cast<int>(bgr[1]),
                static_cast<int>(bgr[0]));
  return text;
}

struct Path {
  std::string label, colour;
  const std::vector<Pose2d>* poses;
};

}  // namespace

std::string SlamTrajectorySvg(const SlamResult& slam, const std::vector<PoseRecord>& frames) {
  const std::vector<Pose2d> truth = TruePoses(frames);
  std::vector<Path> paths = {{"true", "#000000", &truth}, {"odometry", "#a0a0a0", &slam.odometry.poses}};
  for (size_t i = 0; i < slam.methods.size(); ++i) {
    const SlamScore& s = slam.methods[i].Headline(slam.backend);
    // A method that accepted no loop has the odometry's path, which it would only hide.
    if (s.loops_accepted > 0) paths.push_back({slam.methods[i].method, Hex(PaletteColour(i)), &s.poses});
  }
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const Path& p : paths) {
    for (const Pose2d& q : *p.poses) {
      x0 = std::min(x0, q.x_m), x1 = std::max(x1, q.x_m), y0 = std::min(y0, q.y_m), y1 = std::max(y1, q.y_m);
    }
  }
  if (!(x1 > x0) || !(y1 > y0)) return "";
  const double scale = (kSvgWidthPx - 2 * kMarginPx) / (x1 - x0);
  const double height = (y1 - y0) * scale + 2 * kMarginPx;
  std::string svg = "<h3>Trajectories after pose-graph optimisation</h3>\n<svg class=\"trajectories\" width=\"" +
                    Fixed(kSvgWidthPx, 0) + "\" viewBox=\"0 0 " + Fixed(kSvgWidthPx, 0) + " " + Fixed(height, 0) +
                    "\" style=\"max-width:100%;height:auto;border:1px solid #ddd\">\n";
  std::string legend = "<p class=\"legend\">";
  for (const Path& p : paths) {
    // One polyline per recording run: the robot was carried to its dock between runs, not driven.
    std::string points;
    svg += "<g><title>" + EscapeHtml(p.label) + "</title>";
    for (size_t i = 0; i < p.poses->size(); ++i) {
      if (i > 0 && i < frames.size() && frames[i].run != frames[i - 1].run) {
        svg += "<polyline fill=\"none\" stroke=\"" + p.colour + "\" stroke-width=\"1.2\" points=\"" + points + "\"/>";
        points.clear();
      }
      const Pose2d& q = (*p.poses)[i];
      points += (points.empty() ? "" : " ") + Fixed(kMarginPx + (q.x_m - x0) * scale, 1) + "," +
                Fixed(height - kMarginPx - (q.y_m - y0) * scale, 1);
    }
    svg += "<polyline fill=\"none\" stroke=\"" + p.colour + "\" stroke-width=\"1.2\" points=\"" + points + "\"/></g>\n";
    legend += "<span style=\"color:" + p.colour + "\">&#9472;&#9472; " + EscapeHtml(p.label) + "</span>";
  }
  return svg + "</svg>\n" + legend + "</p>\n<p class=\"note\">x right, y up, metres; " + Fixed(x1 - x0, 2) +
         " m across. Each method's path under the headline back end " + EscapeHtml(slam.backend) +
         "; methods that accepted no loop keep the odometry's.</p>\n";
}

}  // namespace hoilcd
