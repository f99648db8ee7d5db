#include "rlrun/tune/regression_tree.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

namespace rlrun::tune {
namespace {

// _splitter.pyx FEATURE_THRESHOLD: values closer than this are one value (no split between
// them; a feature whose values in a node all lie within it is constant there).
constexpr double kFeatureThreshold = 1e-7;
// _tree.pyx EPSILON: a node this pure is a leaf; a split must not lose more than this.
constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

struct Split {
  int feature = -1;
  double threshold = 0;
  size_t position = 0;  // the left child's samples are [start, start + position)
  double proxy = -std::numeric_limits<double>::infinity();
};

class TreeBuilder {
 public:
  TreeBuilder(const Eigen::MatrixXd& x, const Eigen::VectorXd& y, const Eigen::VectorXd& weight,
              const RegressionTreeConfig& config, std::mt19937_64& rng)
      : x_(x), y_(y), weight_(weight), config_(config), rng_(rng) {
    // sklearn's Splitter.init: samples of weight zero (not drawn by the bootstrap) are not
    // in the tree at all.
    for (int s = 0; s < static_cast<int>(y.size()); ++s)
      if (weight(s) > 0) samples_.push_back(s);
    features_.resize(static_cast<size_t>(x.rows()));
    std::iota(features_.begin(), features_.end(), 0);
    total_weight_ = 0;
    for (int s : samples_) total_weight_ += weight(s);
  }

  std::vector<TreeNode> build() {
    if (!samples_.empty()) grow(0, samples_.size(), 0);
    return std::move(nodes_);
  }

 private:
  // DepthFirstTreeBuilder.build for one node and (recursively) its subtree; returns its index.
  int grow(size_t start, size_t end, int depth) {
    const int index = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    double node_weight = 0, weighted_sum = 0;
    for (size_t i = start; i < end; ++i) {
      node_weight += weight_(samples_[i]);
      weighted_sum += weight_(samples_[i]) * y_(samples_[i]);
    }
    const double mean = weighted_sum / node_weight;
    // MSE.node_impurity, taken about the mean (sklearn subtracts sums of squares; the same
    // number without the cancellation).
    double impurity = 0;
    for (size_t i = start; i < end; ++i)
      impurity += weight_(samples_[i]) * (y_(samples_[i]) - mean) * (y_(samples_[i]) - mean);
    impurity /= node_weight;
    const auto n = static_cast<int>(end - start);
    {
      TreeNode& node = nodes_[static_cast<size_t>(index)];
      node.value = mean;
      node.weight = node_weight;
      node.n_samples = n;
    }
    if (depth >= config_.max_depth || n < config_.min_samples_split ||
        n < 2 * config_.min_samples_leaf || impurity <= kEpsilon)
      return index;
    const Split split = best_split(start, end, mean);
    if (split.feature < 0) return index;  // every feature constant here, or leaves too small
    if (improvement(start, end, split, node_weight, impurity) + kEpsilon < 0) return index;
    // The samples going left first (stable: the same tree for the same input).
    std::stable_partition(samples_.begin() + static_cast<std::ptrdiff_t>(start),
                          samples_.begin() + static_cast<std::ptrdiff_t>(end),
                          [&](int s) { return x_(split.feature, s) <= split.threshold; });
    const int left = grow(start, start + split.position, depth + 1);
    const int right = grow(start + split.position, end, depth + 1);
    TreeNode& node = nodes_[static_cast<size_t>(index)];
    node.feature = split.feature;
    node.threshold = split.threshold;
    node.left = left;
    node.right = right;
    return index;
  }

  // BestSplitter.node_split: every feature, in random order (with max_features = all features,
  // the order only breaks ties: the first best split found wins); every boundary between
  // distinct values; the largest MSE.proxy_impurity_improvement, sum_left^2 / w_left +
  // sum_right^2 / w_right (targets taken about the node's mean, for precision).
  Split best_split(size_t start, size_t end, double mean) {
    std::shuffle(features_.begin(), features_.end(), rng_);
    Split best;
    const size_t n = end - start;
    const auto min_leaf = static_cast<size_t>(config_.min_samples_leaf);
    for (int f : features_) {
      sorted_.clear();
      for (size_t i = start; i < end; ++i) sorted_.emplace_back(x_(f, samples_[i]), samples_[i]);
      std::sort(sorted_.begin(), sorted_.end());
      if (sorted_.back().first <= sorted_.front().first + kFeatureThreshold) continue;
      double total_sum = 0, total_weight = 0;
      for (const auto& [v, s] : sorted_) {
        total_sum += weight_(s) * (y_(s) - mean);
        total_weight += weight_(s);
      }
      double left_sum = 0, left_weight = 0;
      for (size_t i = 0; i + 1 < n; ++i) {
        const int s = sorted_[i].second;
        left_sum += weight_(s) * (y_(s) - mean);
        left_weight += weight_(s);
        const double here = sorted_[i].first, next = sorted_[i + 1].first;
        if (next <= here + kFeatureThreshold) continue;  // not a boundary
        if (i + 1 < min_leaf || n - (i + 1) < min_leaf) continue;
        const double right_sum = total_sum - left_sum, right_weight = total_weight - left_weight;
        const double proxy =
            left_sum * left_sum / left_weight + right_sum * right_sum / right_weight;
        if (proxy > best.proxy) {
          best.proxy = proxy;
          best.feature = f;
          best.position = i + 1;
          // Halfway; the lower value when halfway rounds onto the upper one.
          best.threshold = here / 2.0 + next / 2.0;
          if (best.threshold == next || std::isinf(best.threshold)) best.threshold = here;
        }
      }
    }
    return best;
  }

  // Criterion.impurity_improvement: the weighted decrease of impurity the split brings.
  double improvement(size_t start, size_t end, const Split& split, double node_weight,
                     double impurity) const {
    double impurity_left = 0, impurity_right = 0;
    double weight_left = 0, weight_right = 0, sum_left = 0, sum_right = 0;
    for (size_t i = start; i < end; ++i) {
      const int s = samples_[i];
      const bool left = x_(split.feature, s) <= split.threshold;
      (left ? weight_left : weight_right) += weight_(s);
      (left ? sum_left : sum_right) += weight_(s) * y_(s);
    }
    const double mean_left = sum_left / weight_left, mean_right = sum_right / weight_right;
    for (size_t i = start; i < end; ++i) {
      const int s = samples_[i];
      const bool left = x_(split.feature, s) <= split.threshold;
      const double d = y_(s) - (left ? mean_left : mean_right);
      (left ? impurity_left : impurity_right) += weight_(s) * d * d;
    }
    return node_weight / total_weight_ *
           (impurity - impurity_right / node_weight - impurity_left / node_weight);
  }

  const Eigen::MatrixXd& x_;
  const Eigen::VectorXd& y_;
  const Eigen::VectorXd& weight_;
  const RegressionTreeConfig& config_;
  std::mt19937_64& rng_;
  std::vector<int> samples_;
  std::vector<int> features_;
  std::vector<std::pair<double, int>> sorted_;
  std::vector<TreeNode> nodes_;
  double total_weight_ = 0;
};

}  // namespace

std::vector<TreeNode> fit_regression_tree(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                                          const Eigen::VectorXd& weight,
                                          const RegressionTreeConfig& config,
                                          std::mt19937_64& rng) {
  return TreeBuilder(x, y, weight, config, rng).build();
}

double predict(const std::vector<TreeNode>& tree, const Eigen::VectorXd& sample) {
  size_t i = 0;
  while (!tree[i].is_leaf())
    i = static_cast<size_t>(sample(tree[i].feature) <= tree[i].threshold ? tree[i].left
                                                                         : tree[i].right);
  return tree[i].value;
}

}  // namespace rlrun::tune
