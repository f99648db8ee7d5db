#include "rlrun/render/overlay.hpp"

#include <algorithm>
#include <cmath>

namespace rlrun {

namespace {

// Scenes are drawn centred: a cart on its track, a pendulum's pivot, the traffic task's north
// arm running up the middle of the picture to its top edge. The box keeps to the left 40 % of
// the frame so that the middle stays visible.
constexpr double kMaxBoxWidth = 0.4;
constexpr double kMinFontSize = 9.0;

double text_width(cairo_t* cr, const std::string& line) {
  cairo_text_extents_t extents;
  cairo_text_extents(cr, line.c_str(), &extents);
  return extents.x_advance;
}

double widest(cairo_t* cr, const std::vector<std::string>& lines) {
  double width = 0;
  for (const std::string& line : lines) width = std::max(width, text_width(cr, line));
  return width;
}

// Each line wider than `max_text_width` as its pieces between double-space separators
// ("TrafficSignal-v0  fixed-time"), one per line; the other lines as they are.
std::vector<std::string> split_wide_lines(cairo_t* cr, const std::vector<std::string>& lines,
                                          double max_text_width) {
  std::vector<std::string> out;
  for (const std::string& line : lines) {
    if (text_width(cr, line) <= max_text_width) {
      out.push_back(line);
      continue;
    }
    size_t start = 0;
    for (size_t gap; (gap = line.find("  ", start)) != std::string::npos;) {
      if (gap > start) out.push_back(line.substr(start, gap - start));
      start = line.find_first_not_of(' ', gap);
      if (start == std::string::npos) start = line.size();
    }
    if (start < line.size()) out.push_back(line.substr(start));
  }
  return out;
}

}  // namespace

void draw_text_overlay(Frame& frame, const std::vector<std::string>& given) {
  if (given.empty()) return;
  frame.end_scene();
  cairo_t* cr = frame.cairo();
  // 13 px text at Gymnasium's 400-500 px frames, never below 9 px.
  double font_size =
      std::max(kMinFontSize, std::round(std::min(frame.width(), frame.height()) / 32.0));
  cairo_select_font_face(cr, "DejaVu Sans Mono", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, font_size);
  const auto padding = [&] { return 2 * std::round(font_size * 0.4); };
  const double max_width = kMaxBoxWidth * frame.width();
  // Too wide for the corner: the wide lines split at their gaps, then smaller text (>= 9 px).
  const std::vector<std::string> lines = split_wide_lines(cr, given, max_width - padding());
  double width = widest(cr, lines);
  if (width + padding() > max_width) {
    font_size = std::max(kMinFontSize, std::floor(font_size * max_width / (width + padding())));
    cairo_set_font_size(cr, font_size);
    width = widest(cr, lines);
  }
  cairo_font_extents_t font;
  cairo_font_extents(cr, &font);

  const double pad = std::round(font_size * 0.4);
  const double line_height = std::ceil(font.height);
  cairo_rectangle(cr, 0, 0, width + 2 * pad, line_height * lines.size() + 2 * pad);
  cairo_set_source_rgba(cr, 0.0, 0.0, 0.0, 0.55);
  cairo_fill(cr);

  cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
  for (size_t i = 0; i < lines.size(); ++i) {
    cairo_move_to(cr, pad, pad + font.ascent + line_height * i);
    cairo_show_text(cr, lines[i].c_str());
  }
  cairo_new_path(cr);
}

}  // namespace rlrun
