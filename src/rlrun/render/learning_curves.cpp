#include "rlrun/render/learning_curves.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rlrun/core/errors.hpp"
#include "rlrun/render/plot_frame.hpp"

namespace rlrun {

namespace {

constexpr int kPlotWidth = 700, kHeight = 560;
constexpr double kLeft = 90, kTop = 56, kBottom = 64;  // margins; the legend sizes the right one
constexpr const char* kCaption[] = {"line: mean over seeds", "band: lowest to highest seed"};
constexpr int kGridPoints = 200;

struct Band {
  std::vector<double> x, mean, low, high;
};

double interpolate(const std::vector<std::pair<double, double>>& curve, double x) {
  const auto it = std::lower_bound(curve.begin(), curve.end(), x,
                                   [](const auto& p, double v) { return p.first < v; });
  if (it == curve.begin()) return it->second;
  if (it == curve.end()) return curve.back().second;
  const auto& [x1, y1] = *it;
  const auto& [x0, y0] = *(it - 1);
  return x1 == x0 ? y1 : y0 + (y1 - y0) * (x - x0) / (x1 - x0);
}

Band band_of(const CurveGroup& group) {
  std::vector<std::vector<std::pair<double, double>>> seeds;
  for (auto s : group.seeds) {
    s.erase(std::remove_if(
                s.begin(), s.end(),
                [](const auto& p) { return !std::isfinite(p.first) || !std::isfinite(p.second); }),
            s.end());
    std::sort(s.begin(), s.end());
    if (!s.empty()) seeds.push_back(s);
  }
  Band band;
  if (seeds.empty()) return band;
  double from = -std::numeric_limits<double>::infinity(),
         to = std::numeric_limits<double>::infinity();
  for (const auto& s : seeds)
    from = std::max(from, s.front().first), to = std::min(to, s.back().first);
  if (!(to > from)) return band;  // seeds without a common span
  for (int i = 0; i < kGridPoints; ++i) {
    const double x = from + (to - from) * i / (kGridPoints - 1);
    double sum = 0, low = std::numeric_limits<double>::infinity(), high = -low;
    for (const auto& s : seeds) {
      const double y = interpolate(s, x);
      sum += y, low = std::min(low, y), high = std::max(high, y);
    }
    band.x.push_back(x);
    band.mean.push_back(sum / seeds.size());
    band.low.push_back(low);
    band.high.push_back(high);
  }
  return band;
}

// Each band (lowest to highest seed, translucent), then the mean lines on top, clipped to the
// plot area; colours by index.
void draw_bands(cairo_t* cr, const PlotArea& area, const std::vector<Band>& bands) {
  const auto px = [&](double x) { return area.px(x); };
  const auto py = [&](double y) { return area.py(y); };
  cairo_save(cr);
  cairo_rectangle(cr, area.left, area.top, area.width, area.height);
  cairo_clip(cr);
  for (size_t g = 0; g < bands.size(); ++g) {
    const Band& b = bands[g];
    if (b.x.empty()) continue;
    const double* c = kPlotColours[g % 10];
    cairo_set_source_rgba(cr, c[0], c[1], c[2], 0.2);
    cairo_move_to(cr, px(b.x[0]), py(b.high[0]));
    for (size_t i = 1; i < b.x.size(); ++i) cairo_line_to(cr, px(b.x[i]), py(b.high[i]));
    for (size_t i = b.x.size(); i-- > 0;) cairo_line_to(cr, px(b.x[i]), py(b.low[i]));
    cairo_close_path(cr);
    cairo_fill(cr);
  }
  cairo_set_line_width(cr, 2);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (size_t g = 0; g < bands.size(); ++g) {
    const Band& b = bands[g];
    if (b.x.empty()) continue;
    const double* c = kPlotColours[g % 10];
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_move_to(cr, px(b.x[0]), py(b.mean[0]));
    for (size_t i = 1; i < b.x.size(); ++i) cairo_line_to(cr, px(b.x[i]), py(b.mean[i]));
    cairo_stroke(cr);
  }
  cairo_restore(cr);
}

// Right of the plot: one entry per configuration (its colour's band and line, its label), then
// the caption saying what line and band mean.
void draw_legend(cairo_t* cr, const PlotArea& area, const std::vector<std::string>& entries) {
  cairo_set_font_size(cr, 12);
  double ly = kTop + 10;
  for (size_t g = 0; g < entries.size(); ++g) {
    const double* c = kPlotColours[g % 10];
    const double lx = area.left + area.width + 18;
    cairo_set_source_rgba(cr, c[0], c[1], c[2], 0.2);
    cairo_rectangle(cr, lx, ly - 6, 26, 12);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_set_line_width(cr, 2);
    cairo_move_to(cr, lx, ly);
    cairo_line_to(cr, lx + 26, ly);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    draw_text(cr, entries[g], lx + 34, ly, 0, 0.5);
    ly += 22;
  }
  cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
  cairo_set_font_size(cr, 11);
  for (const char* line : kCaption) {
    draw_text(cr, line, area.left + area.width + 18, ly + 6, 0, 0.5);
    ly += 16;
  }
}

}  // namespace

void plot_learning_curves(const std::vector<CurveGroup>& groups, const std::string& y_label,
                          const std::string& title, const std::string& output) {
  if (!is_plot_extension(output))
    throw UsageError("--output " + output + ": expected a .png or .svg file");
  std::vector<Band> bands;
  double x_max = 0, y_min = std::numeric_limits<double>::infinity(), y_max = -y_min;
  for (const CurveGroup& g : groups) {
    bands.push_back(band_of(g));
    const Band& b = bands.back();
    for (size_t i = 0; i < b.x.size(); ++i) {
      x_max = std::max(x_max, b.x[i]);
      y_min = std::min(y_min, b.low[i]);
      y_max = std::max(y_max, b.high[i]);
    }
  }
  if (!std::isfinite(y_min))
    throw RuntimeFailure("nothing to plot: no run has two points of " + y_label);
  if (y_max - y_min < 1e-12) y_min -= 1, y_max += 1;
  const double pad = 0.05 * (y_max - y_min);
  const std::vector<double> x_ticks = nice_ticks(0, x_max),
                            y_ticks = nice_ticks(y_min - pad, y_max + pad);
  PlotArea area;
  area.left = kLeft, area.top = kTop, area.width = kPlotWidth,
  area.height = kHeight - kTop - kBottom;
  area.x_lo = 0, area.x_hi = std::max(x_ticks.back(), x_max);
  area.y_lo = std::min(y_ticks.front(), y_min - pad),
  area.y_hi = std::max(y_ticks.back(), y_max + pad);
  // The legend's entries, measured first: the image grows to fit them.
  std::vector<std::string> entries;
  for (const CurveGroup& g : groups)
    entries.push_back(g.label + " (" + std::to_string(g.seeds.size()) +
                      (g.seeds.size() == 1 ? " seed)" : " seeds)"));
  double legend_width = 0;
  for (const std::string& e : entries)
    legend_width = std::max(legend_width, 34 + text_width(e, 12));
  for (const char* line : kCaption) legend_width = std::max(legend_width, text_width(line, 11));
  const int width = static_cast<int>(kLeft + kPlotWidth + 18 + legend_width + 16);

  PlotCanvas canvas(output, width, kHeight);
  cairo_t* cr = canvas.cr();
  draw_grid(cr, area, x_ticks, y_ticks);
  draw_bands(cr, area, bands);
  draw_titles(cr, area, kHeight, "timesteps", y_label, title);
  draw_legend(cr, area, entries);
  canvas.save();
}

}  // namespace rlrun
