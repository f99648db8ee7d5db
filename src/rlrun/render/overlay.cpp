#include "rlrun/render/overlay.hpp"

#include <algorithm>
#include <cmath>

namespace rlrun {

void draw_text_overlay(Frame& frame, const std::vector<std::string>& lines) {
  if (lines.empty()) return;
  frame.end_scene();
  cairo_t* cr = frame.cairo();
  // 13 px text at Gymnasium's 400-500 px frames, never below 9 px.
  const double font_size =
      std::max(9.0, std::round(std::min(frame.width(), frame.height()) / 32.0));
  cairo_select_font_face(cr, "DejaVu Sans Mono", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, font_size);
  cairo_font_extents_t font;
  cairo_font_extents(cr, &font);

  double text_width = 0;
  for (const std::string& line : lines) {
    cairo_text_extents_t extents;
    cairo_text_extents(cr, line.c_str(), &extents);
    text_width = std::max(text_width, extents.x_advance);
  }
  const double pad = std::round(font_size * 0.4);
  const double line_height = std::ceil(font.height);
  cairo_rectangle(cr, 0, 0, text_width + 2 * pad, line_height * lines.size() + 2 * pad);
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
