#pragma once
// sb3-contrib's conjugate_gradient_solver (sb3_contrib/common/utils.py): an approximate x with
// A x = b for a symmetric positive definite A given as a product A(v), from a small random start
// (1e-4 N(0, 1): "instability issues when the gradient becomes small"), at most max_iter
// iterations, stopping when the squared residual drops under residual_tol. Hestenes and Stiefel
// 1952; Nocedal and Wright, Numerical Optimization, algorithm 5.2.
#include <Eigen/Core>
#include <functional>

#include "rlrun/rng.hpp"

namespace rlrun {

inline Eigen::VectorXf conjugate_gradient(
    const std::function<void(const Eigen::VectorXf&, Eigen::VectorXf&)>& matrix_vector,
    const Eigen::VectorXf& b, int max_iter, Rng& rng, float residual_tol = 1e-10f) {
  Eigen::VectorXf x(b.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) = 1e-4f * static_cast<float>(rng.normal());
  Eigen::VectorXf product;
  matrix_vector(x, product);
  Eigen::VectorXf residual = b - product;
  float residual_sq = residual.squaredNorm();
  if (residual_sq < residual_tol) return x;
  Eigen::VectorXf p = residual;
  for (int i = 0; i < max_iter; ++i) {
    matrix_vector(p, product);
    const float alpha = residual_sq / p.dot(product);
    x += alpha * p;
    if (i == max_iter - 1) break;
    residual -= alpha * product;
    const float new_residual_sq = residual.squaredNorm();
    if (new_residual_sq < residual_tol) break;
    p = residual + (new_residual_sq / residual_sq) * p;
    residual_sq = new_residual_sq;
  }
  return x;
}

}  // namespace rlrun
