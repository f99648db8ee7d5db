#pragma once
// A supersampled canvas for flat-coloured 2D polygons, resolved by a box filter: the picture
// pygame gives when it draws polygons on a large surface and smoothscales it down (Gymnasium's
// CarRacing draws its 1000x800 window and shrinks it to the 96x96 observation). Each output
// pixel averages supersample x supersample point samples, so shared edges of adjacent polygons
// leave no seam (unlike per-polygon antialiasing) and small frames cost little: an observation
// frame is drawn every env step. Fill rule: even-odd on sample centres, as pygame's scanline
// filled_polygon.
#include <cstdint>
#include <span>
#include <vector>

#include "rlrun/frame.hpp"

namespace rlrun {

class PolygonCanvas {
 public:
  // Throws std::invalid_argument unless the sizes are positive and the samples fit (16384
  // per side and 16 per pixel and axis at most).
  PolygonCanvas(int width, int height, int supersample);

  int width() const { return width_; }
  int height() const { return height_; }

  void clear(Rgb color);
  // A polygon with vertices in output pixels (x right, y down; fractions allowed).
  void polygon(std::span<const Point> points, Rgb color);
  // A rectangle [x0, x1) x [y0, y1) in output pixels.
  void rect(double x0, double y0, double x1, double y1, Rgb color);
  // Segments of `width` output pixels between consecutive points.
  void polyline(std::span<const Point> points, double width, Rgb color);

  // Box-filtered RGB bytes, row-major, width * height * 3 of them.
  void resolve(std::span<uint8_t> rgb) const;
  // The same into a Frame of the canvas's size (its RGB24 pixels).
  void resolve(Frame& frame) const;

 private:
  int width_, height_, ss_, sample_width_, sample_height_;
  std::vector<uint32_t> samples_;  // 0x00RRGGBB per sample, row-major
  std::vector<double> crossings_;  // scratch for one sample row
};

}  // namespace rlrun
