#pragma once
// Learning-curve plots for `rlrun plot` (Cairo; PNG or SVG by the file's extension): one line
// per configuration — the mean over its seeds, each seed's curve interpolated linearly onto a
// common grid of timesteps where all seeds have data — with a shaded band from the lowest to the
// highest seed, in the chart frame of render/plot_frame.hpp (ticks, axis titles, title) with a
// legend.
#include <string>
#include <utility>
#include <vector>

#include "rlrun/render/plot_frame.hpp"  // nice_ticks, which used to live here

namespace rlrun {

struct CurveGroup {
  std::string label;
  std::vector<std::vector<std::pair<double, double>>> seeds;  // (timesteps, value) per seed
};

// Throws UsageError for an unknown extension, RuntimeFailure when the file cannot be written
// or no group has two finite points.
void plot_learning_curves(const std::vector<CurveGroup>& groups, const std::string& y_label,
                          const std::string& title, const std::string& output);

}  // namespace rlrun
