// fANOVA's per-tree variances (src/rlrun/tune/fanova.hpp): by hand on a small tree, and against
// Optuna's way of computing them (_fanova/_tree.py: the prediction at the midpoint of every cell
// of the grid the tree's thresholds cut) on trees fitted to random data.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <random>
#include <set>

#include "rlrun/tune/fanova.hpp"

using rlrun::tune::fanova_importances;
using rlrun::tune::FanovaConfig;
using rlrun::tune::TreeNode;
using rlrun::tune::TreePartition;

namespace {

TreeNode split(int feature, double threshold, int left, int right) {
  TreeNode n;
  n.feature = feature, n.threshold = threshold, n.left = left, n.right = right;
  return n;
}

TreeNode leaf(double value) {
  TreeNode n;
  n.value = value;
  return n;
}

// Optuna's computation, brute force: every cell of the grid of all the tree's thresholds, the
// tree's prediction at its midpoint, weighted by its volume; the variance over the cells of
// `group`'s columns of the prediction averaged over the other columns.
struct GridVariances {
  double total = 0;
  double marginal = 0;
};

GridVariances grid_variances(const std::vector<TreeNode>& tree,
                             const std::vector<std::pair<double, double>>& bounds,
                             const std::vector<int>& group) {
  const size_t d = bounds.size();
  std::vector<std::vector<double>> edges(d);
  for (size_t f = 0; f < d; ++f) {
    std::set<double> cuts{bounds[f].first, bounds[f].second};
    for (const TreeNode& n : tree)
      if (n.feature == static_cast<int>(f)) cuts.insert(n.threshold);
    edges[f].assign(cuts.begin(), cuts.end());
  }
  std::vector<size_t> index(d, 0);
  std::map<std::vector<size_t>, std::pair<double, double>> by_group;  // sum of vol*pred, vol
  double sum = 0, sum_sq = 0, volume = 0;
  while (true) {
    Eigen::VectorXd mid(static_cast<Eigen::Index>(d));
    double vol = 1;
    for (size_t f = 0; f < d; ++f) {
      mid(static_cast<Eigen::Index>(f)) = 0.5 * (edges[f][index[f]] + edges[f][index[f] + 1]);
      vol *= edges[f][index[f] + 1] - edges[f][index[f]];
    }
    const double p = rlrun::tune::predict(tree, mid);
    sum += vol * p, sum_sq += vol * p * p, volume += vol;
    std::vector<size_t> key;
    for (int g : group) key.push_back(index[static_cast<size_t>(g)]);
    by_group[key].first += vol * p;
    by_group[key].second += vol;
    size_t f = 0;
    while (f < d && ++index[f] + 1 == edges[f].size()) index[f++] = 0;
    if (f == d) break;
  }
  GridVariances out;
  const double mean = sum / volume;
  out.total = sum_sq / volume - mean * mean;
  for (const auto& [key, s] : by_group) {
    const double m = s.first / s.second;
    out.marginal += s.second / volume * (m - mean) * (m - mean);
  }
  return out;
}

}  // namespace

TEST_CASE("fANOVA's tree variances on a hand-made tree", "[tune]") {
  // x0 <= 0.5: 0; else x1 <= 1: 2, else 4. x0 in [0, 1], x1 in [0, 2].
  const std::vector<TreeNode> tree = {split(0, 0.5, 1, 2), leaf(0), split(1, 1.0, 3, 4), leaf(2),
                                      leaf(4)};
  const TreePartition partition(tree, {{0, 1}, {0, 2}});
  // Volumes 1/2, 1/4, 1/4; mean 1.5.
  CHECK(partition.variance() == Approx(0.5 * 2.25 + 0.25 * 0.25 + 0.25 * 6.25));
  // Averaged over x1: 0 or 3 -> 2.25; averaged over x0: 1 or 2 -> 0.25; the rest (0.25) is
  // their interaction, which neither explains alone.
  CHECK(partition.marginal_variance({0}) == Approx(2.25));
  CHECK(partition.marginal_variance({1}) == Approx(0.25));
  CHECK(partition.marginal_variance({0, 1}) == Approx(partition.variance()));
  // A constant tree has no variance.
  CHECK(TreePartition({leaf(3)}, {{0, 1}}).variance() == 0.0);
}

TEST_CASE("fANOVA's marginal variances equal Optuna's grid of cells on fitted trees", "[tune]") {
  std::mt19937_64 data_rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  for (int round = 0; round < 5; ++round) {
    // Three columns, one pair of them one-hot like a categorical parameter's: y depends on all.
    const int n = 30;
    Eigen::MatrixXd x(4, n);
    Eigen::VectorXd y(n);
    for (int s = 0; s < n; ++s) {
      x(0, s) = u(data_rng);
      x(1, s) = 2 + 3 * u(data_rng);
      const bool hot = u(data_rng) < 0.5;
      x(2, s) = hot, x(3, s) = !hot;
      y(s) = std::sin(4 * x(0, s)) + 0.3 * x(1, s) * x(0, s) + (hot ? 0.5 : 0) + 0.1 * u(data_rng);
    }
    const std::vector<std::pair<double, double>> bounds = {{0, 1}, {2, 5}, {0, 1}, {0, 1}};
    std::mt19937_64 tree_rng(static_cast<uint64_t>(round));
    const auto tree =
        rlrun::tune::fit_regression_tree(x, y, Eigen::VectorXd::Ones(n), {}, tree_rng);
    const TreePartition partition(tree, bounds);
    for (const std::vector<int>& group : {std::vector<int>{0}, {1}, {2, 3}, {0, 1}}) {
      const GridVariances grid = grid_variances(tree, bounds, group);
      CHECK(partition.variance() == Approx(grid.total).epsilon(1e-9));
      CHECK(partition.marginal_variance(group) ==
            Approx(grid.marginal).epsilon(1e-9).margin(1e-12));
    }
  }
}

TEST_CASE("fANOVA importances: the mean share over the trees", "[tune]") {
  // y = x0: x0 explains (nearly) all; x1 only where a node of two samples splits on it as
  // well as on x0 (a tie the feature order breaks, as in sklearn).
  const int n = 40;
  Eigen::MatrixXd x(2, n);
  Eigen::VectorXd y(n);
  for (int s = 0; s < n; ++s) x(0, s) = s / 40.0, x(1, s) = (s * 7 % 40) / 40.0, y(s) = x(0, s);
  FanovaConfig config;
  config.n_trees = 8;
  const auto importances = fanova_importances(x, y, {{0, 1}, {0, 1}}, {{0}, {1}}, config);
  REQUIRE(importances);
  CHECK((*importances)[0] > 0.95);
  CHECK((*importances)[1] < 0.05);
  // The same seed, the same forest.
  CHECK(fanova_importances(x, y, {{0, 1}, {0, 1}}, {{0}, {1}}, config) == importances);
  // Equal values: no tree has variance (Optuna raises).
  CHECK(!fanova_importances(x, Eigen::VectorXd::Constant(n, 2.0), {{0, 1}, {0, 1}}, {{0}, {1}},
                            config));
}
