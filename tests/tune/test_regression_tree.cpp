// The CART regression tree under the fANOVA evaluator (src/rlrun/tune/regression_tree.hpp):
// sklearn's splits on small hand-made data sets.
#include <catch2/catch.hpp>

#include "rlrun/tune/regression_tree.hpp"

using rlrun::tune::fit_regression_tree;
using rlrun::tune::predict;
using rlrun::tune::RegressionTreeConfig;
using rlrun::tune::TreeNode;

namespace {

// One feature per row of `rows`, one sample per column.
Eigen::MatrixXd features(const std::vector<std::vector<double>>& rows) {
  Eigen::MatrixXd x(static_cast<Eigen::Index>(rows.size()),
                    static_cast<Eigen::Index>(rows[0].size()));
  for (size_t f = 0; f < rows.size(); ++f)
    for (size_t s = 0; s < rows[f].size(); ++s)
      x(static_cast<Eigen::Index>(f), static_cast<Eigen::Index>(s)) = rows[f][s];
  return x;
}

Eigen::VectorXd vec(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

std::vector<TreeNode> fit(const std::vector<std::vector<double>>& x, const std::vector<double>& y,
                          std::vector<double> weight = {}, RegressionTreeConfig config = {}) {
  if (weight.empty()) weight.assign(y.size(), 1.0);
  std::mt19937_64 rng(7);
  return fit_regression_tree(features(x), vec(y), vec(weight), config, rng);
}

}  // namespace

TEST_CASE("A regression tree splits halfway between the values that separate the targets",
          "[tune]") {
  const auto tree = fit({{1, 2, 3, 4, 5, 6}}, {1, 1, 1, 5, 5, 5});
  REQUIRE(tree.size() == 3);
  CHECK(tree[0].feature == 0);
  CHECK(tree[0].threshold == 3.5);
  CHECK(tree[0].value == 3.0);
  CHECK(tree[0].n_samples == 6);
  CHECK(tree[0].left == 1);
  CHECK(tree[0].right == 2);
  CHECK(tree[1].is_leaf());
  CHECK(tree[1].value == 1.0);
  CHECK(tree[2].is_leaf());
  CHECK(tree[2].value == 5.0);
  CHECK(predict(tree, vec({3.5})) == 1.0);  // x <= threshold goes left
  CHECK(predict(tree, vec({3.6})) == 5.0);
}

TEST_CASE("A regression tree takes the split of largest variance reduction first", "[tune]") {
  // y = 10 x0 + x1: x0 first, then x1 in both halves; nodes in preorder, left first.
  const auto tree = fit({{0, 0, 1, 1}, {0, 1, 0, 1}}, {0, 1, 10, 11});
  REQUIRE(tree.size() == 7);
  CHECK(tree[0].feature == 0);
  CHECK(tree[0].threshold == 0.5);
  CHECK(tree[1].feature == 1);
  CHECK(tree[1].threshold == 0.5);
  CHECK(tree[0].right == 4);
  CHECK(tree[4].feature == 1);
  std::vector<double> leaves;
  for (const TreeNode& n : tree)
    if (n.is_leaf()) leaves.push_back(n.value);
  CHECK(leaves == std::vector<double>{0, 1, 10, 11});
  CHECK(predict(tree, vec({1, 0})) == 10.0);
}

TEST_CASE("A regression tree weighs samples and leaves out those of weight zero", "[tune]") {
  // Weights as a bootstrap's counts: the mean is weighted.
  const auto weighted = fit({{1, 2}}, {0, 3}, {2, 1});
  CHECK(weighted[0].value == 1.0);
  CHECK(weighted[0].weight == 3.0);
  CHECK(weighted[0].threshold == 1.5);
  // The sample at 2 was not drawn: the split is halfway between 1 and 3.
  const auto dropped = fit({{1, 2, 3}}, {0, 100, 9}, {1, 0, 1});
  CHECK(dropped[0].n_samples == 2);
  CHECK(dropped[0].threshold == 2.0);
  CHECK(dropped[0].value == 4.5);
}

TEST_CASE("A regression tree stops at pure nodes, max_depth and min_samples_leaf", "[tune]") {
  // Equal targets: one leaf.
  CHECK(fit({{1, 2, 3}}, {4, 4, 4}).size() == 1);
  // max_depth 1: the root's split only.
  RegressionTreeConfig shallow;
  shallow.max_depth = 1;
  const auto stump = fit({{1, 2, 3, 4}}, {0, 1, 10, 11}, {}, shallow);
  REQUIRE(stump.size() == 3);
  CHECK(stump[1].value == 0.5);
  // min_samples_leaf 2: the best split 3.5 would leave one sample on the right.
  RegressionTreeConfig two_per_leaf;
  two_per_leaf.min_samples_leaf = 2;
  const auto wide = fit({{1, 2, 3, 4}}, {0, 0, 0, 8}, {}, two_per_leaf);
  CHECK(wide[0].threshold == 2.5);
  CHECK(fit({{1, 2, 3, 4}}, {0, 0, 0, 8})[0].threshold == 3.5);
  // Values closer than sklearn's FEATURE_THRESHOLD (1e-7) are one value: no split.
  CHECK(fit({{1, 1 + 1e-8}}, {0, 1}).size() == 1);
  // A feature constant in the node is never split on.
  const auto tree = fit({{5, 5, 5, 5}, {1, 2, 3, 4}}, {0, 0, 1, 1});
  CHECK(tree[0].feature == 1);
}
