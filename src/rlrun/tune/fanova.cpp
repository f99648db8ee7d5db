#include "rlrun/tune/fanova.hpp"

#include <algorithm>
#include <map>
#include <random>

namespace rlrun::tune {

TreePartition::TreePartition(const std::vector<TreeNode>& tree,
                             const std::vector<std::pair<double, double>>& bounds)
    : n_columns_(static_cast<int>(bounds.size())) {
  if (tree.empty()) return;
  const auto columns = static_cast<size_t>(n_columns_);
  // Depth first from the root's box, the unit cube; a split cuts its column's side at the
  // threshold (_tree.py _get_subspaces), scaled like the column. A threshold outside the
  // bounds (a trial outside its distribution's range) is held at the edge.
  struct Pending {
    int node;
    std::vector<double> lower, upper;
  };
  std::vector<Pending> stack{
      {0, std::vector<double>(columns, 0.0), std::vector<double>(columns, 1.0)}};
  std::vector<double> values;
  while (!stack.empty()) {
    Pending p = std::move(stack.back());
    stack.pop_back();
    const TreeNode& node = tree[static_cast<size_t>(p.node)];
    if (node.is_leaf()) {
      double volume = 1;
      for (size_t c = 0; c < columns; ++c) volume *= p.upper[c] - p.lower[c];
      lower_.insert(lower_.end(), p.lower.begin(), p.lower.end());
      upper_.insert(upper_.end(), p.upper.begin(), p.upper.end());
      values.push_back(node.value);
      volume_.push_back(volume);
      continue;
    }
    const auto f = static_cast<size_t>(node.feature);
    const auto [low, high] = bounds[f];
    const double cut = std::clamp((node.threshold - low) / (high - low), p.lower[f], p.upper[f]);
    Pending right{node.right, p.lower, p.upper};
    right.lower[f] = cut;
    p.upper[f] = cut;
    p.node = node.left;
    stack.push_back(std::move(right));
    stack.push_back(std::move(p));
  }
  // The mean and variance of the leaves' values weighted by their volumes (_FanovaTree.
  // variance); the volumes sum to one but for rounding.
  double total = 0, mean = 0;
  for (size_t l = 0; l < values.size(); ++l) total += volume_[l], mean += volume_[l] * values[l];
  mean /= total;
  for (size_t l = 0; l < values.size(); ++l) {
    volume_[l] /= total;
    centred_value_.push_back(values[l] - mean);
    variance_ += volume_[l] * centred_value_[l] * centred_value_[l];
  }
}

// Optuna evaluates the marginal at the midpoint of every cell of the grid the tree's
// thresholds on `columns` cut, weighted by the cell's size: that is the integral over those
// columns of m(a)^2, m(a) = sum over the leaves whose box holds a of (value - mean) x the
// leaf's share of the other columns' volume. Expanded over pairs of leaves the integral is
// sum_{l, k} c_l c_k |box_l ∩ box_k| (boxes and their overlap in `columns` only), which needs
// no grid: a categorical parameter of n choices would need up to 2^n cells. Leaves with the
// same box in `columns` are merged first.
double TreePartition::marginal_variance(const std::vector<int>& columns) const {
  const auto n_leaves = centred_value_.size();
  const auto stride = static_cast<size_t>(n_columns_);
  std::vector<bool> in_group(stride, false);
  for (int c : columns) in_group[static_cast<size_t>(c)] = true;
  std::map<std::vector<double>, double> weight_of_box;
  std::vector<double> box(2 * columns.size());
  for (size_t l = 0; l < n_leaves; ++l) {
    const double* lower = &lower_[l * stride];
    const double* upper = &upper_[l * stride];
    double rest = 1;  // the leaf's volume in the other columns
    for (size_t c = 0; c < stride; ++c)
      if (!in_group[c]) rest *= upper[c] - lower[c];
    for (size_t i = 0; i < columns.size(); ++i) {
      box[2 * i] = lower[columns[i]];
      box[2 * i + 1] = upper[columns[i]];
    }
    weight_of_box[box] += centred_value_[l] * rest;
  }
  std::vector<const std::vector<double>*> boxes;
  std::vector<double> weights;
  for (const auto& [b, w] : weight_of_box) boxes.push_back(&b), weights.push_back(w);
  double variance = 0;
  for (size_t i = 0; i < boxes.size(); ++i) {
    for (size_t j = i; j < boxes.size(); ++j) {
      double overlap = 1;
      for (size_t k = 0; k < columns.size() && overlap > 0; ++k)
        overlap *= std::max(0.0, std::min((*boxes[i])[2 * k + 1], (*boxes[j])[2 * k + 1]) -
                                     std::max((*boxes[i])[2 * k], (*boxes[j])[2 * k]));
      variance += (i == j ? 1.0 : 2.0) * weights[i] * weights[j] * overlap;
    }
  }
  return std::max(variance, 0.0);  // _fanova.py clips at zero too
}

std::optional<std::vector<double>> fanova_importances(
    const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
    const std::vector<std::pair<double, double>>& bounds,
    const std::vector<std::vector<int>>& groups, const FanovaConfig& config) {
  const auto n = static_cast<int>(y.size());
  std::vector<double> sum_of_fractions(groups.size(), 0.0);
  int counted_trees = 0;
  std::mt19937_64 forest_rng(config.seed);
  for (int t = 0; t < config.n_trees && n > 0; ++t) {
    // Each tree its own generator (sklearn's _set_random_states) and bootstrap: n draws with
    // replacement, the counts as sample weights (forest.py _parallel_build_trees).
    std::mt19937_64 tree_rng(forest_rng());
    std::uniform_int_distribution<int> draw(0, n - 1);
    Eigen::VectorXd counts = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < n; ++i) counts(draw(tree_rng)) += 1;
    const TreePartition partition(fit_regression_tree(x, y, counts, config.tree, tree_rng), bounds);
    // _Fanova.get_importance: trees without variance do not count.
    if (!(partition.variance() > 0)) continue;
    ++counted_trees;
    for (size_t g = 0; g < groups.size(); ++g)
      sum_of_fractions[g] += partition.marginal_variance(groups[g]) / partition.variance();
  }
  if (counted_trees == 0) return std::nullopt;
  for (double& s : sum_of_fractions) s /= counted_trees;
  return sum_of_fractions;
}

}  // namespace rlrun::tune
