#pragma once
// SB3 common/utils.py explained_variance: 1 - Var[y_true - y_pred] / Var[y_true] (population
// variances, as numpy's var); NaN when y_true is constant.
#include <Eigen/Core>
#include <cmath>

namespace rlrun {

template <class A, class B>
double explained_variance(const Eigen::DenseBase<A>& y_pred, const Eigen::DenseBase<B>& y_true) {
  const auto n = static_cast<double>(y_true.size());
  if (n == 0) return std::nan("");
  double mean_true = 0, mean_diff = 0;
  for (Eigen::Index i = 0; i < y_true.size(); ++i) {
    mean_true += y_true.derived().coeff(i);
    mean_diff += y_true.derived().coeff(i) - y_pred.derived().coeff(i);
  }
  mean_true /= n;
  mean_diff /= n;
  double var_true = 0, var_diff = 0;
  for (Eigen::Index i = 0; i < y_true.size(); ++i) {
    const double t = y_true.derived().coeff(i) - mean_true;
    const double d = y_true.derived().coeff(i) - y_pred.derived().coeff(i) - mean_diff;
    var_true += t * t;
    var_diff += d * d;
  }
  return var_true == 0 ? std::nan("") : 1.0 - var_diff / var_true;
}

}  // namespace rlrun
