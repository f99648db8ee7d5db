#pragma once
// The frame every rlrun chart is drawn in (Cairo): a white PNG or SVG canvas chosen by the
// file's extension, DejaVu Sans text, a plot area with "nice" ticks (1-2-5 steps), grid lines,
// tick labels, axis titles and a title. `rlrun plot` (render/learning_curves.hpp) and `rlrun
// tune report` (tune/study_report.hpp) draw their data and legends inside it, so their charts
// look alike.
#include <cairo.h>

#include <string>
#include <vector>

namespace rlrun {

// True for the extensions a chart can be written as: .png and .svg.
bool is_plot_extension(const std::string& path);

// The plot area in pixels and the data range it shows.
struct PlotArea {
  double left = 0, top = 0, width = 1, height = 1;
  double x_lo = 0, x_hi = 1, y_lo = 0, y_hi = 1;
  double px(double x) const { return left + (x - x_lo) / (x_hi - x_lo) * width; }
  double py(double y) const { return top + (1 - (y - y_lo) / (y_hi - y_lo)) * height; }
};

// A white canvas of width x height pixels in the chart font, written to `path` by save().
class PlotCanvas {
 public:
  // Throws UsageError for an extension other than .png and .svg.
  PlotCanvas(const std::string& path, int width, int height);
  ~PlotCanvas();
  PlotCanvas(const PlotCanvas&) = delete;
  PlotCanvas& operator=(const PlotCanvas&) = delete;

  cairo_t* cr() const { return cr_; }
  int width() const { return width_; }
  int height() const { return height_; }
  // Writes the file; throws RuntimeFailure when it cannot be written.
  void save();

 private:
  std::string path_;
  bool png_ = false;
  int width_ = 0, height_ = 0;
  cairo_surface_t* surface_ = nullptr;
  cairo_t* cr_ = nullptr;
};

// How wide `text` is at `font_size` in the chart font (to size a canvas before drawing).
double text_width(const std::string& text, double font_size);
// Draws `text` at (x, y) in the current font and colour; `align_x`, `align_y` in [0, 1]
// place that point on the text's box (0, 0: top left; 0.5, 0.5: centre).
void draw_text(cairo_t* cr, const std::string& text, double x, double y, double align_x,
               double align_y);
// Grid lines and labels at the ticks inside the area's range, and the area's border.
void draw_grid(cairo_t* cr, const PlotArea& area, const std::vector<double>& x_ticks,
               const std::vector<double>& y_ticks);
// The x axis title under the tick labels, the y axis title turned along the left edge, the
// title above the area (centred on it).
void draw_titles(cairo_t* cr, const PlotArea& area, int image_height, const std::string& x_label,
                 const std::string& y_label, const std::string& title);

// Tick positions covering [low, high] with about `target` steps of 1, 2 or 5 x 10^k.
std::vector<double> nice_ticks(double low, double high, int target = 6);
// A tick's label: "%g", with k and M suffixes for large round numbers ("20k", "1.5M").
std::string tick_label(double value, double step);

// matplotlib's tab10, the colours SB3 and Optuna users know from their plots.
inline constexpr double kPlotColours[][3] = {
    {0.122, 0.467, 0.706}, {1.000, 0.498, 0.055}, {0.173, 0.627, 0.173}, {0.839, 0.153, 0.157},
    {0.580, 0.404, 0.741}, {0.549, 0.337, 0.294}, {0.890, 0.467, 0.761}, {0.498, 0.498, 0.498},
    {0.737, 0.741, 0.133}, {0.090, 0.745, 0.812}};

}  // namespace rlrun
