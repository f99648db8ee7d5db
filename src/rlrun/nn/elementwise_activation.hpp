#pragma once
// The activations of nn/activation.hpp applied to a whole matrix and their backward, for
// networks whose layers are not one fused Mlp (BatchRenormMlp: a BatchRenorm sits between the
// activation and the next Linear). The same functions as Mlp's fused kernels: torch's nn.Tanh,
// nn.ReLU, nn.ELU(1.0), nn.LeakyReLU(0.01) and the exact nn.GELU.
#include <Eigen/Core>
#include <cmath>

#include "rlrun/nn/activation.hpp"

namespace rlrun {

// out = act(z), elementwise.
inline void apply_activation(Activation act, const Eigen::MatrixXf& z, Eigen::MatrixXf& out) {
  const auto x = z.array();
  switch (act) {
    case Activation::kTanh: out = x.tanh().matrix(); break;
    case Activation::kReLU: out = x.max(0.0f).matrix(); break;
    case Activation::kELU: out = (x > 0.0f).select(x, x.exp() - 1.0f).matrix(); break;
    case Activation::kLeakyReLU: out = (x > 0.0f).select(x, x * kLeakyReLUSlope).matrix(); break;
    case Activation::kGELU:  // z Phi(z), Phi(z) = erfc(-z / sqrt(2)) / 2
      out = x.unaryExpr([](float v) {
               return 0.5f * v * std::erfc(-v * 0.70710678118654752f);
             }).matrix();
      break;
  }
}

// grad_z = grad * act'(z) for the pre-activation z and output a = act(z).
inline void activation_backward(Activation act, const Eigen::MatrixXf& z, const Eigen::MatrixXf& a,
                                const Eigen::Ref<const Eigen::MatrixXf>& grad,
                                Eigen::MatrixXf& grad_z) {
  const auto g = grad.array();
  switch (act) {
    case Activation::kTanh: grad_z = (g * (1.0f - a.array().square())).matrix(); break;
    case Activation::kReLU: grad_z = (z.array() > 0.0f).select(g, 0.0f).matrix(); break;
    case Activation::kELU:  // exp(z) = a + 1 below zero
      grad_z = (z.array() > 0.0f).select(g, g * (a.array() + 1.0f)).matrix();
      break;
    case Activation::kLeakyReLU:
      grad_z = (z.array() > 0.0f).select(g, g * kLeakyReLUSlope).matrix();
      break;
    case Activation::kGELU:  // Phi(z) + z phi(z)
      grad_z = (g * z.array().unaryExpr([](float v) {
                 return 0.5f * std::erfc(-v * 0.70710678118654752f) +
                        v * 0.39894228040143268f * std::exp(-0.5f * v * v);
               })).matrix();
      break;
  }
}

}  // namespace rlrun
