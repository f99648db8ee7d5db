// write_history_plot (study_report.hpp): Optuna's plot_optimization_history
// (optuna/visualization/_optimization_history.py, Optuna 3.1) in the chart frame of `rlrun plot`
// (render/plot_frame.hpp): a marker per COMPLETE trial at (number, value) and the best value so
// far (np.maximum / np.minimum.accumulate over them). Optuna joins the best values with straight
// segments; a step is what "best so far" means, so rlrun draws one.
#include <algorithm>
#include <cmath>
#include <limits>

#include "rlrun/core/errors.hpp"
#include "rlrun/render/plot_frame.hpp"
#include "rlrun/tune/study_report.hpp"

namespace rlrun::tune {
namespace {

constexpr int kPlotWidth = 700, kHeight = 560;
constexpr double kLeft = 90, kTop = 56, kBottom = 64;  // as render/learning_curves.cpp
constexpr double kMarkerRadius = 3.5;
const double* const kPointColour = kPlotColours[0];  // blue, Optuna's first trace
const double* const kBestColour = kPlotColours[3];   // red, its second
constexpr double kPrunedGrey = 0.72;

struct Point {
  double x, y;
};

void marker(cairo_t* cr, double x, double y) {
  cairo_new_sub_path(cr);
  cairo_arc(cr, x, y, kMarkerRadius, 0, 2 * M_PI);
}

// The legend's rows: a sample of the mark, then its text.
enum class Mark { kPoint, kLine, kPruned };

void legend_row(cairo_t* cr, Mark mark, const std::string& label, double x, double y) {
  if (mark == Mark::kLine) {
    cairo_set_source_rgb(cr, kBestColour[0], kBestColour[1], kBestColour[2]);
    cairo_set_line_width(cr, 2);
    cairo_move_to(cr, x, y);
    cairo_line_to(cr, x + 26, y);
    cairo_stroke(cr);
  } else {
    if (mark == Mark::kPoint)
      cairo_set_source_rgb(cr, kPointColour[0], kPointColour[1], kPointColour[2]);
    else
      cairo_set_source_rgb(cr, kPrunedGrey, kPrunedGrey, kPrunedGrey);
    marker(cr, x + 13, y);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  draw_text(cr, label, x + 34, y, 0, 0.5);
}

}  // namespace

void write_history_plot(const std::string& name, StudyDirection direction,
                        const std::vector<FrozenTrial>& trials, const std::string& path,
                        bool show_pruned) {
  if (!is_plot_extension(path)) throw UsageError(path + ": expected a .png or .svg file");
  // Non-finite values (an objective of inf) have no place on the axis: left out, and out of
  // the best so far.
  std::vector<Point> complete, pruned, best;
  for (const FrozenTrial& t : trials) {
    const auto number = static_cast<double>(t.number);
    if (t.state == TrialState::kComplete && t.value() && std::isfinite(*t.value())) {
      complete.push_back({number, *t.value()});
      const double v = *t.value();
      const bool better =
          best.empty() ||
          (direction == StudyDirection::kMaximize ? v > best.back().y : v < best.back().y);
      best.push_back({number, better ? v : best.back().y});
    } else if (show_pruned && t.state == TrialState::kPruned && t.last_step()) {
      const double v = t.intermediate_values.rbegin()->second;
      if (std::isfinite(v)) pruned.push_back({number, v});
    }
  }

  // Ranges: every mark inside, with a margin; trial numbers are whole, so are the x ticks.
  double x_max = 0, y_min = std::numeric_limits<double>::infinity(), y_max = -y_min;
  for (const auto* points : {&complete, &pruned})
    for (const Point& p : *points)
      x_max = std::max(x_max, p.x), y_min = std::min(y_min, p.y), y_max = std::max(y_max, p.y);
  if (!std::isfinite(y_min)) y_min = 0, y_max = 1;  // nothing to show: empty axes, as Optuna
  if (y_max - y_min < 1e-12) y_min -= 1, y_max += 1;
  const double y_pad = 0.05 * (y_max - y_min), x_pad = std::max(0.5, 0.02 * x_max);
  std::vector<double> x_ticks;
  for (double t : nice_ticks(0, x_max))
    if (std::abs(t - std::round(t)) < 1e-9) x_ticks.push_back(std::round(t));
  const std::vector<double> y_ticks = nice_ticks(y_min - y_pad, y_max + y_pad);
  PlotArea area;
  area.left = kLeft, area.top = kTop, area.width = kPlotWidth,
  area.height = kHeight - kTop - kBottom;
  area.x_lo = -x_pad, area.x_hi = x_max + x_pad;
  area.y_lo = std::min(y_ticks.front(), y_min - y_pad);
  area.y_hi = std::max(y_ticks.back(), y_max + y_pad);

  std::vector<std::pair<Mark, std::string>> legend = {{Mark::kPoint, "objective value"},
                                                      {Mark::kLine, "best value"}};
  if (show_pruned) legend.emplace_back(Mark::kPruned, "pruned trial (last report)");
  double legend_width = 0;
  for (const auto& [mark, label] : legend)
    legend_width = std::max(legend_width, 34 + text_width(label, 12));
  PlotCanvas canvas(path, static_cast<int>(kLeft + kPlotWidth + 18 + legend_width + 16), kHeight);
  cairo_t* cr = canvas.cr();
  draw_grid(cr, area, x_ticks, y_ticks);

  cairo_save(cr);
  cairo_rectangle(cr, area.left, area.top, area.width, area.height);
  cairo_clip(cr);
  cairo_set_source_rgb(cr, kPrunedGrey, kPrunedGrey, kPrunedGrey);
  for (const Point& p : pruned) marker(cr, area.px(p.x), area.py(p.y));
  cairo_fill(cr);
  cairo_set_source_rgb(cr, kPointColour[0], kPointColour[1], kPointColour[2]);
  for (const Point& p : complete) marker(cr, area.px(p.x), area.py(p.y));
  cairo_fill(cr);
  if (!best.empty()) {
    cairo_set_source_rgb(cr, kBestColour[0], kBestColour[1], kBestColour[2]);
    cairo_set_line_width(cr, 2);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_MITER);
    cairo_move_to(cr, area.px(best[0].x), area.py(best[0].y));
    for (size_t i = 1; i < best.size(); ++i) {
      cairo_line_to(cr, area.px(best[i].x), area.py(best[i - 1].y));
      cairo_line_to(cr, area.px(best[i].x), area.py(best[i].y));
    }
    cairo_stroke(cr);
  }
  cairo_restore(cr);

  draw_titles(cr, area, kHeight, "trial", "objective value", name);
  cairo_set_font_size(cr, 12);
  double y = kTop + 10;
  for (const auto& [mark, label] : legend) {
    legend_row(cr, mark, label, area.left + area.width + 18, y);
    y += 22;
  }
  canvas.save();
}

}  // namespace rlrun::tune
