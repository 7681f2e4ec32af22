#include "hoilcd/bench/report/chart.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "hoilcd/core/util/error.h"

// Axes, ticks and legends are drawn here with OpenCV primitives: cv::plot::Plot2d (opencv_contrib)
// draws a single series without tick labels or legend, and no plotting library is a dependency.
namespace hoilcd {
namespace chart {
namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr int kInkLevel = 35;    // grey level of frame, ticks and text
constexpr int kGridLevel = 228;  // grey level of grid lines
constexpr int kTickLengthPx = 5;
constexpr int kLineThicknessPx = 2;
constexpr double kMarkerRadiusPx = 4.5;
constexpr double kLegendMarginPx = 10.0;

// An interval that can be drawn: [0, 1] when empty, widened around a single value.
Range Drawable(Range r) {
  if (!(r.lo <= r.hi)) return {0.0, 1.0};
  if (r.Span() <= 1e-12 * std::max(1.0, std::abs(r.lo))) {
    const double half = r.lo != 0.0 ? 0.1 * std::abs(r.lo) : 0.5;
    return {r.lo - half, r.hi + half};
  }
  return r;
}

double NiceStep(double lo, double hi, int max_count) {
  auto count = [&](double step) { return std::floor(hi / step + 1e-9) - std::ceil(lo / step - 1e-9) + 1.0; };
  double previous = 0.0;
  for (double decade = std::pow(10.0, std::floor(std::log10((hi - lo) / max_count)) - 1.0);; decade *= 10.0) {
    for (const double mantissa : {1.0, 2.0, 5.0}) {
      const double step = decade * mantissa;
      if (count(step) <= max_count) return count(step) < 2.0 && previous > 0.0 ? previous : step;
      previous = step;
    }
  }
}

std::string FormatTick(double value, double step) {
  if (std::abs(value) < 1e-9 * step) value = 0.0;  // no "-0"
  std::array<char, 32> text{};
  if (std::abs(value) >= 1e6 || step < 1e-5) {
    std::snprintf(text.data(), text.size(), "%.3g", value);
    std::string compact = text.data();  // "2e+06" -> "2e6", "5e-07" -> "5e-7"
    const std::size_t e = compact.find('e');
    if (e == std::string::npos) return compact;
    std::string exponent = compact.substr(e + 1);
    const bool negative = exponent[0] == '-';
    exponent.erase(0, exponent.find_first_not_of("+-0"));
    return compact.substr(0, e + 1) + (negative ? "-" : "") + exponent;
  } else {
    const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
    std::snprintf(text.data(), text.size(), "%.*f", decimals, value);
  }
  return text.data();
}

// Text rotated a quarter turn counter-clockwise, centred on `centre`, dark on the white margin.
void PutTextVertical(cv::Mat& image, const std::string& text, cv::Point centre, double scale) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, kFont, scale, 1, &baseline);
  cv::Mat tile(size.height + baseline + 4, size.width + 4, CV_8UC3, White());
  cv::putText(tile, text, cv::Point(2, size.height + 2), kFont, scale, Grey(kInkLevel), 1, cv::LINE_AA);
  cv::Mat rotated;
  cv::rotate(tile, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
  const cv::Rect wanted(centre.x - rotated.cols / 2, centre.y - rotated.rows / 2, rotated.cols, rotated.rows);
  const cv::Rect visible = wanted & cv::Rect(0, 0, image.cols, image.rows);
  if (visible.empty()) return;
  cv::Mat target = image(visible);
  cv::min(target, rotated(visible - wanted.tl()), target);
}

// Filled marker; shape 0 circle, 1 square, 2 triangle up, 3 diamond, 4 triangle down (cycling).
void Marker(cv::Mat& image, cv::Point2d centre, int shape, double radius, const cv::Scalar& colour) {
  if (!Finite(centre) || centre.x < -radius || centre.y < -radius || centre.x > image.cols + radius ||
      centre.y > image.rows + radius) {
    return;
  }
  static const std::array<std::vector<cv::Point2d>, 4> kShapes = {{
      {{-0.85, -0.85}, {0.85, -0.85}, {0.85, 0.85}, {-0.85, 0.85}},
      {{0.0, -1.2}, {1.1, 0.75}, {-1.1, 0.75}},
      {{0.0, -1.25}, {1.25, 0.0}, {0.0, 1.25}, {-1.25, 0.0}},
      {{0.0, 1.2}, {1.1, -0.75}, {-1.1, -0.75}},
  }};
  const int kind = shape % 5;
  if (kind == 0) {
    cv::circle(image, SubPixel(centre), cvRound(radius * kSubPixels), colour, cv::FILLED, cv::LINE_AA, kShift);
    return;
  }
  std::vector<cv::Point> polygon;
  for (const cv::Point2d& v : kShapes[kind - 1]) polygon.push_back(SubPixel(centre + v * radius));
  cv::fillConvexPoly(image, polygon, colour, cv::LINE_AA, kShift);
}

std::vector<std::string> TickLabels(const std::vector<double>& ticks, double span) {
  const double step = ticks.size() >= 2 ? ticks[1] - ticks[0] : span;
  std::vector<std::string> labels;
  for (const double t : ticks) labels.push_back(FormatTick(t, step));
  return labels;
}

int WidestText(const std::vector<std::string>& texts, double scale) {
  int widest = 0;
  for (const std::string& t : texts) widest = std::max(widest, TextSize(t, scale).width);
  return widest;
}

double LabelScale(const PlotOptions& o) { return o.font_scale * 1.15; }
double TitleScale(const PlotOptions& o) { return o.font_scale * 1.3; }

Axes MakeAxes(const PlotOptions& o, const AxesSpec& spec) {
  const int tick_h = TextSize("0", o.font_scale).height;
  const int label_h = TextSize("Ag", LabelScale(o)).height + 4;
  const int top = o.title.empty() ? 16 : 14 + TextSize(o.title, TitleScale(o)).height + 14;
  const int bottom = kTickLengthPx + 7 + tick_h + (o.x_label.empty() ? 0 : 14 + label_h) + 10;
  Axes a;
  a.inset_px = spec.inset_px;
  int y_labels_w = TextSize("0.00", o.font_scale).width;
  int x_label_half_w = 0;
  // Margins depend on the tick labels, which depend on the frame size: two passes settle it.
  for (int pass = 0; pass < 2; ++pass) {
    const int left = kTickLengthPx + 7 + y_labels_w + (o.y_label.empty() ? 0 : 14 + label_h) + 10;
    const int right = std::max(20, x_label_half_w + 6);
    a.frame = cv::Rect(left, top, std::max(20, o.width_px - left - right), std::max(20, o.height_px - top - bottom));
    a.x = spec.x;
    a.y = spec.y;
    if (spec.equal_aspect) {
      const double w = a.frame.width - 1 - 2 * a.inset_px;
      const double h = a.frame.height - 1 - 2 * a.inset_px;
      const double px_per_unit = std::min(w / a.x.Span(), h / a.y.Span());
      const double x_mid = 0.5 * (a.x.lo + a.x.hi);
      const double y_mid = 0.5 * (a.y.lo + a.y.hi);
      a.x = {x_mid - 0.5 * w / px_per_unit, x_mid + 0.5 * w / px_per_unit};
      a.y = {y_mid - 0.5 * h / px_per_unit, y_mid + 0.5 * h / px_per_unit};
    }
    const int y_count = std::clamp(a.frame.height / (5 * tick_h), 2, 10);
    a.y_ticks = NiceTicks(a.y.lo, a.y.hi, y_count);
    a.y_tick_labels = TickLabels(a.y_ticks, a.y.Span());
    if (!spec.categories.empty()) {
      a.x_ticks.clear();
      for (std::size_t i = 0; i < spec.categories.size(); ++i) a.x_ticks.push_back(i);
      a.x_tick_labels = spec.categories;
    } else {
      for (int count = std::clamp(a.frame.width / 40, 2, 12); count >= 2; --count) {
        a.x_ticks = NiceTicks(a.x.lo, a.x.hi, count);
        a.x_tick_labels = TickLabels(a.x_ticks, a.x.Span());
        const int widest = WidestText(a.x_tick_labels, o.font_scale);
        if (static_cast<int>(a.x_ticks.size()) * (widest + 18) <= a.frame.width) break;
      }
    }
    y_labels_w = WidestText(a.y_tick_labels, o.font_scale);
    x_label_half_w = a.x_tick_labels.empty() ? 0 : TextSize(a.x_tick_labels.back(), o.font_scale).width / 2;
  }
  a.y_tick_labels_width_px = y_labels_w;
  return a;
}

void DrawGrid(cv::Mat& canvas, const Axes& a, bool vertical_lines) {
  cv::Mat roi = canvas(a.frame);
  for (const double t : a.y_ticks) {
    const int v = cvRound(a.ToLocal(a.x.lo, t).y);
    cv::line(roi, {0, v}, {roi.cols - 1, v}, Grey(kGridLevel), 1);
  }
  if (!vertical_lines) return;
  for (const double t : a.x_ticks) {
    const int u = cvRound(a.ToLocal(t, a.y.lo).x);
    cv::line(roi, {u, 0}, {u, roi.rows - 1}, Grey(kGridLevel), 1);
  }
}

void DrawFrame(cv::Mat& canvas, const Axes& a, const PlotOptions& o) {
  const cv::Scalar ink = Grey(kInkLevel);
  const cv::Rect& f = a.frame;
  cv::rectangle(canvas, f, ink, 1);
  for (std::size_t i = 0; i < a.x_ticks.size(); ++i) {
    const int u = f.x + cvRound(a.ToLocal(a.x_ticks[i], a.y.lo).x);
    const int bottom = f.y + f.height - 1;
    cv::line(canvas, {u, bottom}, {u, bottom + kTickLengthPx}, ink, 1);
    PutText(canvas, a.x_tick_labels[i], {static_cast<double>(u), bottom + kTickLengthPx + 7.0}, 0.5, 0.0, o.font_scale,
            ink);
  }
  for (std::size_t i = 0; i < a.y_ticks.size(); ++i) {
    const int v = f.y + cvRound(a.ToLocal(a.x.lo, a.y_ticks[i]).y);
    cv::line(canvas, {f.x - kTickLengthPx, v}, {f.x, v}, ink, 1);
    PutText(canvas, a.y_tick_labels[i], {f.x - kTickLengthPx - 7.0, static_cast<double>(v)}, 1.0, 0.5, o.font_scale,
            ink);
  }
  const int tick_h = TextSize("0", o.font_scale).height;
  if (!o.x_label.empty()) {
    const double v = f.y + f.height + kTickLengthPx + 7 + tick_h + 14;
    PutText(canvas, o.x_label, {f.x + 0.5 * f.width, v}, 0.5, 0.0, LabelScale(o), ink);
  }
  if (!o.y_label.empty()) {
    const int label_h = TextSize("Ag", LabelScale(o)).height + 4;
    const int u = f.x - kTickLengthPx - 7 - a.y_tick_labels_width_px - 14 - label_h / 2;
    PutTextVertical(canvas, o.y_label, {u, f.y + f.height / 2}, LabelScale(o));
  }
  if (!o.title.empty()) {
    PutText(canvas, o.title, {f.x + 0.5 * f.width, 14.0}, 0.5, 0.0, TitleScale(o), ink);
  }
}

cv::Size LegendSize(const std::vector<LegendItem>& items, double font_scale) {
  int widest = 0;
  for (const LegendItem& item : items) widest = std::max(widest, TextSize(item.label, font_scale).width);
  const int row_h = TextSize("0", font_scale).height + 10;
  return {10 + 30 + 8 + widest + 10, 6 + static_cast<int>(items.size()) * row_h + 4};
}

// Puts the legend in the frame position (corners first) that covers the fewest data pixels;
// returns how many it covers.
int DrawLegend(cv::Mat& canvas, const Axes& a, const std::vector<LegendItem>& items, const cv::Mat& data_mask,
               double font_scale) {
  if (items.empty()) return 0;
  const cv::Size size = LegendSize(items, font_scale);
  const double m = kLegendMarginPx;
  const double right = a.frame.width - size.width - m;
  const double bottom = a.frame.height - size.height - m;
  const double mid_x = 0.5 * (a.frame.width - size.width);
  const double mid_y = 0.5 * (a.frame.height - size.height);
  const std::array<cv::Point2d, 8> candidates = {
      {{right, m}, {m, m}, {right, bottom}, {m, bottom}, {mid_x, m}, {mid_x, bottom}, {right, mid_y}, {m, mid_y}}};
  cv::Rect best;
  int best_covered = std::numeric_limits<int>::max();
  for (const cv::Point2d& c : candidates) {
    const cv::Rect r =
        cv::Rect(cvRound(c.x), cvRound(c.y), size.width, size.height) & cv::Rect(0, 0, a.frame.width, a.frame.height);
    const int covered = r.empty() ? 0 : cv::countNonZero(data_mask(r));
    if (covered < best_covered) {
      best_covered = covered;
      best = r;
    }
  }
  if (best.empty()) return 0;
  cv::Mat roi = canvas(a.frame);
  cv::Mat box = roi(best);
  cv::addWeighted(box, 0.12, cv::Mat(box.size(), box.type(), White()), 0.88, 0.0, box);
  cv::rectangle(roi, best, Grey(170), 1);
  const int row_h = TextSize("0", font_scale).height + 10;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const LegendItem& item = items[i];
    const double v = best.y + 6 + (i + 0.5) * row_h;
    const cv::Point2d sample_l(best.x + 10.0, v);
    const cv::Point2d sample_r(best.x + 40.0, v);
    if (item.line) Segment(roi, sample_l, sample_r, item.colour, kLineThicknessPx);
    if (item.marker >= 0) {
      Marker(roi, 0.5 * (sample_l + sample_r), item.marker, kMarkerRadiusPx, item.colour);
    }
    if (item.swatch) {
      cv::rectangle(roi, cv::Rect(best.x + 17, cvRound(v) - 6, 16, 12), item.colour, cv::FILLED);
    }
    PutText(roi, item.label, {best.x + 48.0, v}, 0.0, 0.5, font_scale, Grey(kInkLevel));
  }
  return best_covered;
}

cv::Mat RenderOnce(const PlotOptions& o, const AxesSpec& spec, bool vertical_grid,
                   const std::vector<LegendItem>& legend, const DrawData& draw_data, cv::Rect* plot_area_px,
                   int* legend_covered_px) {
  const Axes axes = MakeAxes(o, spec);
  cv::Mat canvas(o.height_px, o.width_px, CV_8UC3, White());
  DrawGrid(canvas, axes, vertical_grid);
  cv::Mat roi = canvas(axes.frame);
  const cv::Mat before = roi.clone();
  draw_data(roi, axes);
  cv::Mat difference;
  cv::absdiff(roi, before, difference);
  cv::Mat data_mask;
  cv::cvtColor(difference, data_mask, cv::COLOR_BGR2GRAY);
  DrawFrame(canvas, axes, o);
  *legend_covered_px = o.legend ? DrawLegend(canvas, axes, legend, data_mask, o.font_scale) : 0;
  if (plot_area_px != nullptr) *plot_area_px = axes.frame;
  return canvas;
}

bool HasSpread(const Series& s) { return !s.y_low.empty(); }

void CheckSeries(const Series& s, std::size_t expected_y) {
  HOILCD_CHECK_MSG(s.y.size() == expected_y,
                   "series '" << s.label << "' has " << s.y.size() << " y values, expected " << expected_y);
  HOILCD_CHECK_MSG(s.y_low.size() == s.y_high.size() && (s.y_low.empty() || s.y_low.size() == s.y.size()),
                   "series '" << s.label << "': y_low and y_high must both be empty or match y");
}

cv::Scalar SeriesColour(const std::vector<Series>& series, std::size_t i) {
  return series[i].colour.value_or(PaletteColour(i));
}

void DrawErrorBar(cv::Mat& roi, cv::Point2d low, cv::Point2d high, double cap_half_px, const cv::Scalar& colour) {
  Segment(roi, low, high, colour, 1);
  Segment(roi, low - cv::Point2d(cap_half_px, 0), low + cv::Point2d(cap_half_px, 0), colour, 1);
  Segment(roi, high - cv::Point2d(cap_half_px, 0), high + cv::Point2d(cap_half_px, 0), colour, 1);
}

void DrawBand(cv::Mat& roi, const Axes& a, const Series& s, const cv::Scalar& colour) {
  std::vector<std::vector<cv::Point>> runs(1);
  std::vector<cv::Point> lower;
  auto close_run = [&] {
    runs.back().insert(runs.back().end(), lower.rbegin(), lower.rend());
    lower.clear();
    if (runs.back().size() >= 3)
      runs.emplace_back();
    else
      runs.back().clear();
  };
  for (std::size_t i = 0; i < s.y.size(); ++i) {
    const cv::Point2d high = a.ToLocal(s.x[i], s.y_high[i]);
    const cv::Point2d low = a.ToLocal(s.x[i], s.y_low[i]);
    if (!Finite(high) || !Finite(low)) {
      close_run();
      continue;
    }
    runs.back().push_back(SubPixel(high));
    lower.push_back(SubPixel(low));
  }
  close_run();
  runs.pop_back();
  if (runs.empty()) return;
  cv::Mat overlay = roi.clone();
  cv::fillPoly(overlay, runs, colour, cv::LINE_AA, kShift);
  cv::addWeighted(overlay, 0.22, roi, 0.78, 0.0, roi);
}

}  // namespace

cv::Scalar Grey(int level) { return cv::Scalar(level, level, level); }
cv::Scalar White() { return Grey(255); }

Range FromOption(const std::optional<std::pair<double, double>>& option, Range data) {
  if (option) return {option->first, option->second};
  return Drawable(data);
}

cv::Size TextSize(const std::string& text, double scale) {
  int baseline = 0;
  return cv::getTextSize(text, kFont, scale, 1, &baseline);
}

// Text whose box (cap height, no descender) is placed so that the point at fractions
// (h_align, v_align) of it lands on anchor: (0, 0) top-left, (0.5, 0.5) centre, (1, 1) bottom-right.
void PutText(cv::Mat& image, const std::string& text, cv::Point2d anchor, double h_align, double v_align, double scale,
             const cv::Scalar& colour) {
  const cv::Size size = TextSize(text, scale);
  const cv::Point origin(cvRound(anchor.x - h_align * size.width), cvRound(anchor.y + (1.0 - v_align) * size.height));
  cv::putText(image, text, origin, kFont, scale, colour, 1, cv::LINE_AA);
}

// Pixel coordinates in fixed point, kept far inside int range.
cv::Point SubPixel(cv::Point2d p) {
  const double limit = 1e6 * kSubPixels;
  return {cvRound(std::clamp(p.x * kSubPixels, -limit, limit)), cvRound(std::clamp(p.y * kSubPixels, -limit, limit))};
}

// Nearest whole pixel, kept far inside int range.
cv::Point Pixel(cv::Point2d p) {
  const double limit = 1e6;
  return {cvRound(std::clamp(p.x, -limit, limit)), cvRound(std::clamp(p.y, -limit, limit))};
}

bool Finite(cv::Point2d p) { return std::isfinite(p.x) && std::isfinite(p.y); }

// Anti-aliased segment clipped to the image first, so points far outside the range draw right.
void Segment(cv::Mat& image, cv::Point2d a, cv::Point2d b, const cv::Scalar& colour, int thickness) {
  if (!Finite(a) || !Finite(b)) return;
  const double limit = 1e15;
  auto to_long = [&](cv::Point2d p) {
    return cv::Point2l(std::llround(std::clamp(p.x * kSubPixels, -limit, limit)),
                       std::llround(std::clamp(p.y * kSubPixels, -limit, limit)));
  };
  cv::Point2l pa = to_long(a);
  cv::Point2l pb = to_long(b);
  const int64_t margin = 8 * (1 << kShift);  // keep thick line ends whole at the border
  const cv::Point2l offset(margin, margin);
  pa += offset;
  pb += offset;
  if (!cv::clipLine(cv::Size2l(image.cols * (1 << kShift) + 2 * margin, image.rows * (1 << kShift) + 2 * margin), pa,
                    pb)) {
    return;
  }
  pa -= offset;
  pb -= offset;
  cv::line(image, cv::Point(static_cast<int>(pa.x), static_cast<int>(pa.y)),
           cv::Point(static_cast<int>(pb.x), static_cast<int>(pb.y)), colour, thickness, cv::LINE_AA, kShift);
}

// Draws the figure; when the legend would hide data, the y range is automatic and the legend
// is small next to the plot, draws it again with room for the legend at the top.
cv::Mat Render(const PlotOptions& o, AxesSpec spec, bool vertical_grid, const std::vector<LegendItem>& legend,
               const DrawData& draw_data, cv::Rect* plot_area_px) {
  HOILCD_CHECK_MSG(o.Check().empty(), o.Check());
  int covered = 0;
  cv::Mat canvas = RenderOnce(o, spec, vertical_grid, legend, draw_data, plot_area_px, &covered);
  if (covered == 0 || o.y_range || !o.legend || legend.empty()) return canvas;
  const double needed_px = LegendSize(legend, o.font_scale).height + 2 * kLegendMarginPx;
  const double usable_px = o.height_px * 0.8;
  if (needed_px > 0.45 * usable_px) return canvas;
  spec.y.hi = spec.y.lo + spec.y.Span() / (1.0 - needed_px / usable_px);
  return RenderOnce(o, spec, vertical_grid, legend, draw_data, plot_area_px, &covered);
}

}  // namespace chart

using namespace chart;  // the building blocks above, for the charts below

cv::Scalar PaletteColour(std::size_t index) {
  // Okabe & Ito's eight colour-blind-safe colours, then four of Tol's "muted" scheme that differ
  // from them (hoilcd bench runs nine methods; twelve series before a colour repeats).
  static const std::array<cv::Scalar, 12> kPalette = {{
      {178, 114, 0},    // blue
      {0, 94, 213},     // vermillion
      {115, 158, 0},    // bluish green
      {0, 159, 230},    // orange
      {167, 121, 204},  // reddish purple
      {233, 180, 86},   // sky blue
      {0, 0, 0},        // black
      {66, 228, 240},   // yellow
      {85, 34, 136},    // wine
      {136, 34, 51},    // indigo
      {51, 153, 153},   // olive
      {51, 119, 17},    // green
  }};
  return kPalette[index % kPalette.size()];
}

std::vector<double> NiceTicks(double lo, double hi, int max_count) {
  HOILCD_CHECK_MSG(max_count >= 2, "max_count " << max_count);
  if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi) return {};
  if (lo == hi) return {lo};
  const double step = NiceStep(lo, hi, max_count);
  std::vector<double> ticks;
  const double first = std::ceil(lo / step - 1e-9);
  const double last = std::floor(hi / step + 1e-9);
  for (double k = first; k <= last; k += 1.0) ticks.push_back(k * step);
  return ticks;
}

namespace {

// "" for an unset range or a finite one with first < second, else what is expected.
std::string RangeProblem(const std::optional<std::pair<double, double>>& range) {
  const bool valid =
      !range || (std::isfinite(range->first) && std::isfinite(range->second) && range->first < range->second);
  return valid ? "" : "must be finite with first < second";
}

}  // namespace

PlotOptions::PlotOptions() { Table().FillDefaults(this); }

const OptionTable<PlotOptions>& PlotOptions::Table() {
  using O = PlotOptions;
  using R = OptionRange;
  static const OptionTable<O> table =
      OptionTable<O>()
          .Add("title", &O::title, "", {}, "drawn above the axes; empty: none")
          .Add("x_label", &O::x_label, "", {}, "below the x axis; empty: none")
          .Add("y_label", &O::y_label, "", {}, "left of the y axis, rotated; empty: none")
          .Add("width_px", &O::width_px, 800, "px", R::Closed(200, 10000), "image width")
          .Add("height_px", &O::height_px, 560, "px", R::Closed(150, 10000), "image height")
          .Rule("x_range", [](const O& o) { return RangeProblem(o.x_range); })
          .Rule("y_range", [](const O& o) { return RangeProblem(o.y_range); })
          .Add("equal_aspect", &O::equal_aspect, false,
               "one data unit is as long on both axes (ranges are widened to fit)")
          .Add("legend", &O::legend, true, "a legend of labelled series, in the corner hiding least data")
          .Add("font_scale", &O::font_scale, 0.5, "", R::Closed(0.4, 2),
               "tick-label size (OpenCV Hershey scale); labels and title are larger");
  return table;
}

std::string PlotOptions::Check() const { return Table().FirstProblem(*this); }

cv::Mat LinePlot(const std::vector<Series>& series, const PlotOptions& options, cv::Rect* plot_area_px) {
  Range x, y;
  std::vector<LegendItem> legend;
  for (std::size_t i = 0; i < series.size(); ++i) {
    const Series& s = series[i];
    CheckSeries(s, s.x.size());
    for (std::size_t j = 0; j < s.y.size(); ++j) {
      if (!std::isfinite(s.x[j])) continue;
      x.Add(s.x[j]);
      y.Add(s.y[j]);
      if (HasSpread(s)) {
        y.Add(s.y_low[j]);
        y.Add(s.y_high[j]);
      }
    }
    if (!s.label.empty()) {
      legend.push_back(
          {s.label, SeriesColour(series, i), s.line || !s.markers, s.markers ? static_cast<int>(i) : -1, false});
    }
  }
  AxesSpec spec;
  spec.x = FromOption(options.x_range, x);
  spec.y = FromOption(options.y_range, y);
  spec.equal_aspect = options.equal_aspect;
  const DrawData draw = [&series](cv::Mat& roi, const Axes& a) {
    for (std::size_t i = 0; i < series.size(); ++i) {
      if (series[i].band && HasSpread(series[i])) {
        DrawBand(roi, a, series[i], SeriesColour(series, i));
      }
    }
    for (std::size_t i = 0; i < series.size(); ++i) {
      const Series& s = series[i];
      const cv::Scalar colour = SeriesColour(series, i);
      for (std::size_t j = 0; s.line && j + 1 < s.y.size(); ++j) {
        Segment(roi, a.ToLocal(s.x[j], s.y[j]), a.ToLocal(s.x[j + 1], s.y[j + 1]), colour, kLineThicknessPx);
      }
      for (std::size_t j = 0; HasSpread(s) && !s.band && j < s.y.size(); ++j) {
        DrawErrorBar(roi, a.ToLocal(s.x[j], s.y_low[j]), a.ToLocal(s.x[j], s.y_high[j]), 4.0, colour);
      }
      for (std::size_t j = 0; s.markers && j < s.y.size(); ++j) {
        Marker(roi, a.ToLocal(s.x[j], s.y[j]), static_cast<int>(i), kMarkerRadiusPx, colour);
      }
    }
  };
  return Render(options, spec, true, legend, draw, plot_area_px);
}

cv::Mat BarPlot(const std::vector<std::string>& groups, const std::vector<Series>& series, const PlotOptions& options,
                cv::Rect* plot_area_px) {
  HOILCD_CHECK_MSG(!groups.empty(), "BarPlot needs at least one group");
  Range y;
  y.Add(0.0);
  std::vector<LegendItem> legend;
  for (std::size_t i = 0; i < series.size(); ++i) {
    const Series& s = series[i];
    CheckSeries(s, groups.size());
    for (std::size_t j = 0; j < s.y.size(); ++j) {
      y.Add(s.y[j]);
      if (HasSpread(s)) {
        y.Add(s.y_low[j]);
        y.Add(s.y_high[j]);
      }
    }
    if (!s.label.empty()) legend.push_back({s.label, SeriesColour(series, i), false, -1, true});
  }
  AxesSpec spec;
  spec.categories = groups;
  spec.inset_px = 0.0;
  spec.x = {-0.5, groups.size() - 0.5};
  if (options.y_range) {
    spec.y = {options.y_range->first, options.y_range->second};
  } else {
    spec.y = Drawable(y);
    const double headroom = 0.06 * spec.y.Span();
    if (spec.y.lo < 0.0) spec.y.lo -= headroom;
    if (spec.y.hi > 0.0) spec.y.hi += headroom;
  }
  const DrawData draw = [&series](cv::Mat& roi, const Axes& a) {
    const double group_width = 0.8;
    const double bar_width = group_width / std::max<std::size_t>(1, series.size());
    for (std::size_t i = 0; i < series.size(); ++i) {
      const Series& s = series[i];
      const cv::Scalar colour = SeriesColour(series, i);
      for (std::size_t g = 0; g < s.y.size(); ++g) {
        const double left = g - 0.5 * group_width + i * bar_width;
        const cv::Point2d top_left = a.ToLocal(left, s.y[g]);
        const cv::Point2d bottom_right = a.ToLocal(left + bar_width, 0.0);
        if (!Finite(top_left)) continue;
        const cv::Point p0 = Pixel(top_left) + cv::Point(1, 0);
        const cv::Point p1 = Pixel(bottom_right) - cv::Point(1, 0);
        cv::rectangle(roi, cv::Rect(p0, p1), colour, cv::FILLED);
      }
    }
    for (std::size_t i = 0; i < series.size(); ++i) {
      const Series& s = series[i];
      for (std::size_t g = 0; HasSpread(s) && g < s.y.size(); ++g) {
        const double centre = g - 0.5 * group_width + (i + 0.5) * bar_width;
        const double cap_px = 0.25 * bar_width * (a.frame.width - 1) / a.x.Span();
        DrawErrorBar(roi, a.ToLocal(centre, s.y_low[g]), a.ToLocal(centre, s.y_high[g]), std::min(6.0, cap_px),
                     Grey(kInkLevel));
      }
    }
    if (a.y.lo < 0.0) {
      const double v = a.ToLocal(0.0, 0.0).y;
      Segment(roi, {0.0, v}, {roi.cols - 1.0, v}, Grey(kInkLevel), 1);
    }
  };
  return Render(options, spec, false, legend, draw, plot_area_px);
}

}  // namespace hoilcd
