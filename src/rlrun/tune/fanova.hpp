#pragma once
// fANOVA (Hutter, Hoos and Leyton-Brown 2014, "An Efficient Approach for Assessing
// Hyperparameter Importance") as Optuna 3.1's default importance evaluator computes it
// (optuna/importance/_fanova/_fanova.py, _tree.py): a random forest fitted to the trials
// (sklearn's RandomForestRegressor: bootstrap samples, every feature tried at every split,
// trees grown until their leaves are pure) and, per tree, the share of the variance of its
// prediction over the search space that one parameter explains alone — the variance of the
// prediction averaged over all the other parameters, the "marginal" — averaged over the trees.
//
// The space is a box: one column per numeric parameter and one per choice of a categorical
// one (one-hot); a parameter is a group of columns. The forest's random numbers are rlrun's
// (std::mt19937_64), not numpy's: importances differ from Optuna's in the digits, not in
// what matters.
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "rlrun/tune/regression_tree.hpp"

namespace rlrun::tune {

// FanovaImportanceEvaluator's defaults.
struct FanovaConfig {
  int n_trees = 64;
  RegressionTreeConfig tree;  // max_depth 64, min_samples_split 2, min_samples_leaf 1
  uint64_t seed = 0;
};

// A tree's partition of the search space: its leaves, each a box with the tree's value there
// (_FanovaTree's statistics, computed from the leaves instead of the node traversal).
class TreePartition {
 public:
  // `bounds`: per column (low, high), low < high; the tree's thresholds cut them.
  TreePartition(const std::vector<TreeNode>& tree,
                const std::vector<std::pair<double, double>>& bounds);

  // _FanovaTree.variance: the variance of the tree's prediction over the (uniform) box.
  double variance() const { return variance_; }
  // _FanovaTree.get_marginal_variance: the variance over `columns` of the prediction averaged
  // over every other column.
  double marginal_variance(const std::vector<int>& columns) const;

 private:
  int n_columns_ = 0;
  // Per leaf, its box in the unit cube (each column scaled to [0, 1]: variances are ratios of
  // volumes, which the scaling does not change) and its value minus the tree's mean.
  std::vector<double> lower_, upper_;  // leaf-major: leaf * n_columns_ + column
  std::vector<double> centred_value_;
  std::vector<double> volume_;
  double variance_ = 0;
};

// The importance of each group of columns (one per parameter), not normalised: the mean over
// the trees of positive variance of marginal_variance(group) / variance() (_Fanova.
// get_importance). `x`: one trial per column (columns x trials); `y`: their values. Empty when
// every tree's variance is zero (Optuna raises "Encountered zero total variance in all trees").
std::optional<std::vector<double>> fanova_importances(
    const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
    const std::vector<std::pair<double, double>>& bounds,
    const std::vector<std::vector<int>>& groups, const FanovaConfig& config);

}  // namespace rlrun::tune
