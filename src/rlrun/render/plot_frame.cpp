#include "rlrun/render/plot_frame.hpp"

#include <cairo-svg.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "rlrun/core/errors.hpp"

namespace rlrun {

namespace {
constexpr const char* kFont = "DejaVu Sans";
}  // namespace

bool is_plot_extension(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  return ext == ".png" || ext == ".svg";
}

PlotCanvas::PlotCanvas(const std::string& path, int width, int height)
    : path_(path), width_(width), height_(height) {
  if (!is_plot_extension(path)) throw UsageError(path + ": expected a .png or .svg file");
  png_ = std::filesystem::path(path).extension() == ".png";
  surface_ = png_ ? cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height)
                  : cairo_svg_surface_create(path.c_str(), width, height);
  cr_ = cairo_create(surface_);
  cairo_set_source_rgb(cr_, 1, 1, 1);
  cairo_paint(cr_);
  cairo_select_font_face(cr_, kFont, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
}

PlotCanvas::~PlotCanvas() {
  if (cr_) cairo_destroy(cr_);
  if (surface_) cairo_surface_destroy(surface_);
}

void PlotCanvas::save() {
  cairo_destroy(cr_);
  cr_ = nullptr;
  cairo_status_t status = CAIRO_STATUS_SUCCESS;
  if (png_) status = cairo_surface_write_to_png(surface_, path_.c_str());
  cairo_surface_finish(surface_);  // an SVG surface writes its file here
  if (status == CAIRO_STATUS_SUCCESS) status = cairo_surface_status(surface_);
  cairo_surface_destroy(surface_);
  surface_ = nullptr;
  if (status != CAIRO_STATUS_SUCCESS)
    throw RuntimeFailure("cannot write " + path_ + ": " + cairo_status_to_string(status));
}

double text_width(const std::string& text, double font_size) {
  cairo_surface_t* scratch = cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1);
  cairo_t* measure = cairo_create(scratch);
  cairo_select_font_face(measure, kFont, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(measure, font_size);
  cairo_text_extents_t extents;
  cairo_text_extents(measure, text.c_str(), &extents);
  cairo_destroy(measure);
  cairo_surface_destroy(scratch);
  return extents.x_advance;
}

void draw_text(cairo_t* cr, const std::string& text, double x, double y, double align_x,
               double align_y) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, text.c_str(), &e);
  cairo_move_to(cr, x - align_x * e.width - e.x_bearing, y - align_y * e.height - e.y_bearing);
  cairo_show_text(cr, text.c_str());
}

void draw_grid(cairo_t* cr, const PlotArea& area, const std::vector<double>& x_ticks,
               const std::vector<double>& y_ticks) {
  cairo_set_font_size(cr, 12);
  cairo_set_line_width(cr, 1);
  const double x_step = x_ticks.size() > 1 ? x_ticks[1] - x_ticks[0] : 1;
  const double y_step = y_ticks.size() > 1 ? y_ticks[1] - y_ticks[0] : 1;
  for (double t : x_ticks) {
    if (t < area.x_lo || t > area.x_hi) continue;
    cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
    cairo_move_to(cr, area.px(t), area.top);
    cairo_line_to(cr, area.px(t), area.top + area.height);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    draw_text(cr, tick_label(t, x_step), area.px(t), area.top + area.height + 8, 0.5, 0);
  }
  for (double t : y_ticks) {
    if (t < area.y_lo || t > area.y_hi) continue;
    cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
    cairo_move_to(cr, area.left, area.py(t));
    cairo_line_to(cr, area.left + area.width, area.py(t));
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    draw_text(cr, tick_label(t, y_step), area.left - 8, area.py(t), 1, 0.5);
  }
  cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
  cairo_rectangle(cr, area.left, area.top, area.width, area.height);
  cairo_stroke(cr);
}

void draw_titles(cairo_t* cr, const PlotArea& area, int image_height, const std::string& x_label,
                 const std::string& y_label, const std::string& title) {
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_set_font_size(cr, 14);
  draw_text(cr, x_label, area.left + area.width / 2, image_height - 18, 0.5, 1);
  cairo_save(cr);
  cairo_translate(cr, 22, area.top + area.height / 2);
  cairo_rotate(cr, -M_PI / 2);
  draw_text(cr, y_label, 0, 0, 0.5, 0.5);
  cairo_restore(cr);
  cairo_set_font_size(cr, 16);
  draw_text(cr, title, area.left + area.width / 2, 20, 0.5, 0.5);
}

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
  for (double t = std::ceil(low / step - 1e-9) * step; t <= high + step * 1e-9; t += step)
    ticks.push_back(t);
  return ticks;
}

std::string tick_label(double value, double step) {
  char buffer[32];
  const double a = std::abs(value);
  if (a >= 1e6 && step >= 1e5)
    std::snprintf(buffer, sizeof buffer, "%gM", value / 1e6);
  else if (a >= 1e3 && step >= 100)
    std::snprintf(buffer, sizeof buffer, "%gk", value / 1e3);
  else
    std::snprintf(buffer, sizeof buffer, "%g", std::abs(value) < step * 1e-6 ? 0.0 : value);
  return buffer;
}

}  // namespace rlrun
