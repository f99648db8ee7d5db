#pragma once
// The central-difference check every NatureCNN gradient test runs (the CNN's own, PPO's, DQN's and
// the off-policy algorithms' CnnPolicy): a loss computed in double through the reference
// (nature_cnn_reference.hpp), differentiated over parameters spread across every layer.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <string>

#include "rlrun/nn/nature_cnn.hpp"

namespace rlrun::test {

// Checks net.grads() against central differences of `loss` at about `samples` parameters
// (every (num_params / samples + 1)-th), with Catch's Approx margin and epsilon; returns how
// many were checked. The features are piecewise linear in any one parameter, so a small step
// gives the exact slope unless it crosses a ReLU's kink; the step is taken on the float
// parameter and divided by the float difference, which the double reference then
// differentiates exactly.
inline int check_cnn_gradient(const NatureCnn& net,
                              const std::function<double(const NatureCnn&)>& loss,
                              const std::string& what, int samples, double margin, double epsilon) {
  int checked = 0;
  for (Eigen::Index k = 0; k < net.num_params(); k += net.num_params() / samples + 1) {
    NatureCnn plus = net, minus = net;
    const float h = 1e-6f * std::max(1.0f, std::abs(net.params()(k)));
    plus.params()(k) += h;
    minus.params()(k) -= h;
    const double numeric =
        (loss(plus) - loss(minus)) / (static_cast<double>(plus.params()(k)) - minus.params()(k));
    INFO(what << " parameter " << k);
    CHECK(net.grads()(k) == Approx(numeric).margin(margin).epsilon(epsilon));
    ++checked;
  }
  return checked;
}

}  // namespace rlrun::test
