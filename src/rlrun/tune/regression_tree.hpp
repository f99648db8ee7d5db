#pragma once
// A CART regression tree as scikit-learn grows one inside RandomForestRegressor (sklearn 1.2,
// sklearn/tree/_tree.pyx DepthFirstTreeBuilder, _splitter.pyx BestSplitter, _criterion.pyx
// MSE): the split of largest variance reduction over every feature, thresholds halfway between
// neighbouring distinct values, `x <= threshold` goes left, grown depth first until a node is
// pure, too small or too deep. Optuna's fANOVA evaluator (tune/fanova.hpp) reads the tree's
// partition of the search space.
#include <cstdint>
#include <random>
#include <vector>

#include <Eigen/Core>

namespace rlrun::tune {

struct RegressionTreeConfig {
  int max_depth = 64;         // the root is at depth 0
  int min_samples_split = 2;  // a node with fewer (distinct) samples is a leaf
  int min_samples_leaf = 1;   // neither child of a split may have fewer
};

// A node of the tree; children come after their parent (preorder, left subtree first, as
// sklearn numbers them).
struct TreeNode {
  int feature = -1;      // -1: a leaf
  double threshold = 0;  // x[feature] <= threshold goes left
  int left = -1, right = -1;
  double value = 0;   // the weighted mean of the node's targets
  double weight = 0;  // the sum of its samples' weights
  int n_samples = 0;  // its samples with a non-zero weight
  bool is_leaf() const { return feature < 0; }
};

// Fits a tree to the samples `x` (one per column, features x samples) and targets `y`, each
// sample weighted by `weight` (a bootstrap's counts; zero drops the sample). `rng` orders the
// features at each node, which only decides between equally good splits (as in sklearn).
std::vector<TreeNode> fit_regression_tree(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                                          const Eigen::VectorXd& weight,
                                          const RegressionTreeConfig& config, std::mt19937_64& rng);

// The value of the leaf `sample` (one column of features) falls into.
double predict(const std::vector<TreeNode>& tree, const Eigen::VectorXd& sample);

}  // namespace rlrun::tune
