#include "rlrun/render/learning_curves.hpp"

#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "rlrun/core/errors.hpp"

namespace rlrun {

namespace {

constexpr int kPlotWidth = 700, kHeight = 560;
constexpr double kLeft = 90, kTop = 56, kBottom = 64;  // margins; the legend sizes the right one
constexpr const char* kCaption[] = {"line: mean over seeds", "band: lowest to highest seed"};
constexpr int kGridPoints = 200;
// matplotlib's tab10, the colours SB3 users know from their plots.
constexpr double kColours[][3] = {{0.122, 0.467, 0.706}, {1.000, 0.498, 0.055}, {0.173, 0.627, 0.173},
                                  {0.839, 0.153, 0.157}, {0.580, 0.404, 0.741}, {0.549, 0.337, 0.294},
                                  {0.890, 0.467, 0.761}, {0.498, 0.498, 0.498}, {0.737, 0.741, 0.133},
                                  {0.090, 0.745, 0.812}};

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
    s.erase(std::remove_if(s.begin(), s.end(),
                           [](const auto& p) { return !std::isfinite(p.first) || !std::isfinite(p.second); }),
            s.end());
    std::sort(s.begin(), s.end());
    if (!s.empty()) seeds.push_back(s);
  }
  Band band;
  if (seeds.empty()) return band;
  double from = -std::numeric_limits<double>::infinity(), to = std::numeric_limits<double>::infinity();
  for (const auto& s : seeds) from = std::max(from, s.front().first), to = std::min(to, s.back().first);
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

std::string tick_label(double v, double step) {
  char buffer[32];
  const double a = std::abs(v);
  if (a >= 1e6 && step >= 1e5) std::snprintf(buffer, sizeof buffer, "%gM", v / 1e6);
  else if (a >= 1e3 && step >= 100) std::snprintf(buffer, sizeof buffer, "%gk", v / 1e3);
  else std::snprintf(buffer, sizeof buffer, "%g", std::abs(v) < step * 1e-6 ? 0.0 : v);
  return buffer;
}

void text(cairo_t* cr, const std::string& s, double x, double y, double align_x, double align_y) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_move_to(cr, x - align_x * e.width - e.x_bearing, y - align_y * e.height - e.y_bearing);
  cairo_show_text(cr, s.c_str());
}

}  // namespace

std::vector<double> nice_ticks(double low, double high, int target) {
  if (!(high > low)) high = low + 1;
  const double raw = (high - low) / target;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = magnitude;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * magnitude >= raw) {
      step = m * magnitude;
      break;
    }
  std::vector<double> ticks;
  for (double t = std::ceil(low / step - 1e-9) * step; t <= high + step * 1e-9; t += step) ticks.push_back(t);
  return ticks;
}

void plot_learning_curves(const std::vector<CurveGroup>& groups, const std::string& y_label,
                          const std::string& title, const std::string& output) {
  const std::string ext = std::filesystem::path(output).extension().string();
  if (ext != ".png" && ext != ".svg")
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
  if (!std::isfinite(y_min)) throw RuntimeFailure("nothing to plot: no run has two points of " + y_label);
  if (y_max - y_min < 1e-12) y_min -= 1, y_max += 1;
  const double pad = 0.05 * (y_max - y_min);
  const std::vector<double> x_ticks = nice_ticks(0, x_max), y_ticks = nice_ticks(y_min - pad, y_max + pad);
  const double x_lo = 0, x_hi = std::max(x_ticks.back(), x_max);
  const double y_lo = std::min(y_ticks.front(), y_min - pad), y_hi = std::max(y_ticks.back(), y_max + pad);
  // The legend's entries, measured first: the image grows to fit them.
  std::vector<std::string> entries;
  for (const CurveGroup& g : groups)
    entries.push_back(g.label + " (" + std::to_string(g.seeds.size()) +
                      (g.seeds.size() == 1 ? " seed)" : " seeds)"));
  double legend_width = 0;
  {
    cairo_surface_t* scratch = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1);
    cairo_t* measure = cairo_create(scratch);
    cairo_select_font_face(measure, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(measure, 12);
    for (const std::string& e : entries) {
      cairo_text_extents_t extents;
      cairo_text_extents(measure, e.c_str(), &extents);
      legend_width = std::max(legend_width, 34 + extents.x_advance);
    }
    cairo_set_font_size(measure, 11);
    for (const char* line : kCaption) {
      cairo_text_extents_t extents;
      cairo_text_extents(measure, line, &extents);
      legend_width = std::max(legend_width, extents.x_advance);
    }
    cairo_destroy(measure);
    cairo_surface_destroy(scratch);
  }
  const int kWidth = static_cast<int>(kLeft + kPlotWidth + 18 + legend_width + 16);
  const double plot_w = kPlotWidth, plot_h = kHeight - kTop - kBottom;
  const auto px = [&](double x) { return kLeft + (x - x_lo) / (x_hi - x_lo) * plot_w; };
  const auto py = [&](double y) { return kTop + (1 - (y - y_lo) / (y_hi - y_lo)) * plot_h; };

  cairo_surface_t* surface = ext == ".svg" ? cairo_svg_surface_create(output.c_str(), kWidth, kHeight)
                                           : cairo_image_surface_create(CAIRO_FORMAT_RGB24, kWidth, kHeight);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);

  // Grid, ticks and tick labels.
  cairo_set_font_size(cr, 12);
  cairo_set_line_width(cr, 1);
  const double x_step = x_ticks.size() > 1 ? x_ticks[1] - x_ticks[0] : 1;
  const double y_step = y_ticks.size() > 1 ? y_ticks[1] - y_ticks[0] : 1;
  for (double t : x_ticks) {
    cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
    cairo_move_to(cr, px(t), kTop);
    cairo_line_to(cr, px(t), kTop + plot_h);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    text(cr, tick_label(t, x_step), px(t), kTop + plot_h + 8, 0.5, 0);
  }
  for (double t : y_ticks) {
    if (t < y_lo || t > y_hi) continue;
    cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
    cairo_move_to(cr, kLeft, py(t));
    cairo_line_to(cr, kLeft + plot_w, py(t));
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    text(cr, tick_label(t, y_step), kLeft - 8, py(t), 1, 0.5);
  }
  cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
  cairo_rectangle(cr, kLeft, kTop, plot_w, plot_h);
  cairo_stroke(cr);

  // Bands, then mean lines on top, clipped to the plot area.
  cairo_save(cr);
  cairo_rectangle(cr, kLeft, kTop, plot_w, plot_h);
  cairo_clip(cr);
  for (size_t g = 0; g < bands.size(); ++g) {
    const Band& b = bands[g];
    if (b.x.empty()) continue;
    const double* c = kColours[g % 10];
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
    const double* c = kColours[g % 10];
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_move_to(cr, px(b.x[0]), py(b.mean[0]));
    for (size_t i = 1; i < b.x.size(); ++i) cairo_line_to(cr, px(b.x[i]), py(b.mean[i]));
    cairo_stroke(cr);
  }
  cairo_restore(cr);

  // Axis labels, title, legend (right of the plot: one entry per configuration).
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_set_font_size(cr, 14);
  text(cr, "timesteps", kLeft + plot_w / 2, kHeight - 18, 0.5, 1);
  cairo_save(cr);
  cairo_translate(cr, 22, kTop + plot_h / 2);
  cairo_rotate(cr, -M_PI / 2);
  text(cr, y_label, 0, 0, 0.5, 0.5);
  cairo_restore(cr);
  cairo_set_font_size(cr, 16);
  text(cr, title, kLeft + plot_w / 2, 20, 0.5, 0.5);
  cairo_set_font_size(cr, 12);
  double ly = kTop + 10;
  for (size_t g = 0; g < groups.size(); ++g) {
    const double* c = kColours[g % 10];
    const double lx = kLeft + plot_w + 18;
    cairo_set_source_rgba(cr, c[0], c[1], c[2], 0.2);
    cairo_rectangle(cr, lx, ly - 6, 26, 12);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_set_line_width(cr, 2);
    cairo_move_to(cr, lx, ly);
    cairo_line_to(cr, lx + 26, ly);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    text(cr, entries[g], lx + 34, ly, 0, 0.5);
    ly += 22;
  }
  cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
  cairo_set_font_size(cr, 11);
  for (const char* line : kCaption) {
    text(cr, line, kLeft + plot_w + 18, ly + 6, 0, 0.5);
    ly += 16;
  }

  cairo_destroy(cr);
  cairo_status_t status = CAIRO_STATUS_SUCCESS;
  if (ext == ".png") status = cairo_surface_write_to_png(surface, output.c_str());
  cairo_surface_finish(surface);
  if (status == CAIRO_STATUS_SUCCESS) status = cairo_surface_status(surface);
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS)
    throw RuntimeFailure("cannot write " + output + ": " + cairo_status_to_string(status));
}

}  // namespace rlrun
