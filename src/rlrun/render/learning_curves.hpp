#pragma once
// Learning-curve plots for `rlrun plot` (Cairo; PNG or SVG by the file's extension): one line
// per configuration — the mean over its seeds, each seed's curve interpolated linearly onto a
// common grid of timesteps where all seeds have data — with a shaded band from the lowest to the
// highest seed; "nice" axis ticks (1-2-5 steps), axis labels, a legend and a title.
#include <string>
#include <utility>
#include <vector>

namespace rlrun {

struct CurveGroup {
  std::string label;
  std::vector<std::vector<std::pair<double, double>>> seeds;  // (timesteps, value) per seed
};

// Throws UsageError for an unknown extension, RuntimeFailure when the file cannot be written
// or no group has two finite points.
void plot_learning_curves(const std::vector<CurveGroup>& groups, const std::string& y_label,
                          const std::string& title, const std::string& output);

// Tick positions covering [low, high] with about `target` steps of 1, 2 or 5 x 10^k.
std::vector<double> nice_ticks(double low, double high, int target = 6);

}  // namespace rlrun
