// Adam, RMSprop and clip_grad_norm against updates computed by hand (in double) from the torch
// formulas (torch/optim/adam.py, rmsprop.py, torch/nn/utils/clip_grad.py).
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "rlrun/nn/adam.hpp"
#include "rlrun/nn/clip_grad.hpp"
#include "rlrun/nn/param_vector.hpp"
#include "rlrun/nn/rmsprop.hpp"

namespace rlrun {
namespace {

// Gradient of step t (1-based) for parameter k: varies in sign and size.
double grad_at(int t, int k) {
  return (k % 2 == 0 ? 1.0 : -1.0) * (0.1 * (k + 1)) * (1.0 + 0.5 * t) + (t == 2 ? 0.3 : 0.0);
}

TEST_CASE("Adam matches torch.optim.Adam step by step", "[nn]") {
  ParamVector a(3, 0.0f), b(2, 0.0f);
  a.value << 0.5f, -1.0f, 2.0f;
  b.value << 0.0f, 3.0f;
  const AdamConfig cfg{0.9, 0.999, 1e-5};
  Adam adam({a.block(), b.block()}, cfg);
  std::vector<double> p = {0.5, -1.0, 2.0, 0.0, 3.0};
  std::vector<double> m(5, 0.0), v(5, 0.0);
  const double lr = 3e-4;
  for (int t = 1; t <= 3; ++t) {
    for (int k = 0; k < 5; ++k) {
      const float g = static_cast<float>(grad_at(t, k));
      if (k < 3)
        a.grad(k) = g;
      else
        b.grad(k - 3) = g;
      const double gd = g;
      m[k] = 0.9 * m[k] + 0.1 * gd;
      v[k] = 0.999 * v[k] + 0.001 * gd * gd;
      const double m_hat_step = lr / (1.0 - std::pow(0.9, t));
      const double denom = std::sqrt(v[k]) / std::sqrt(1.0 - std::pow(0.999, t)) + 1e-5;
      p[k] -= m_hat_step * m[k] / denom;
    }
    adam.step(static_cast<float>(lr));
    CHECK(adam.steps() == t);
    for (int k = 0; k < 5; ++k) {
      const float got = k < 3 ? a.value(k) : b.value(k - 3);
      INFO("step " << t << " param " << k);
      CHECK(got == Approx(p[k]).epsilon(1e-6).margin(1e-7));
      CHECK((k < 3 ? adam.exp_avg()[0](k) : adam.exp_avg()[1](k - 3)) ==
            Approx(m[k]).epsilon(1e-5));
      CHECK((k < 3 ? adam.exp_avg_sq()[0](k) : adam.exp_avg_sq()[1](k - 3)) ==
            Approx(v[k]).epsilon(1e-5));
    }
    if (t == 1) {
      // The first Adam step moves every parameter by ~lr against its gradient's sign.
      CHECK(a.value(0) == Approx(0.5 - lr).epsilon(1e-4));
      CHECK(a.value(1) == Approx(-1.0 + lr).epsilon(1e-4));
    }
  }

  // Checkpoint round trip: a copy of the state continues identically.
  ParamVector a2 = a, b2 = b;
  Adam resumed({a2.block(), b2.block()}, cfg);
  resumed.exp_avg() = adam.exp_avg();
  resumed.exp_avg_sq() = adam.exp_avg_sq();
  resumed.set_steps(adam.steps());
  adam.step(1e-3f);
  resumed.step(1e-3f);
  CHECK(a2.value == a.value);
  CHECK(b2.value == b.value);
}

TEST_CASE("RmsProp matches torch.optim.RMSprop step by step", "[nn]") {
  ParamVector w(4, 1.0f);
  w.value << 1.0f, -2.0f, 0.25f, 0.0f;
  RmsProp opt({w.block()});
  CHECK(opt.config().alpha == 0.99);
  CHECK(opt.config().eps == 1e-5);
  std::vector<double> p = {1.0, -2.0, 0.25, 0.0};
  std::vector<double> v(4, 0.0);
  const double lr = 7e-4;
  for (int t = 1; t <= 3; ++t) {
    for (int k = 0; k < 4; ++k) {
      const float g = static_cast<float>(grad_at(t, k));
      w.grad(k) = g;
      v[k] = 0.99 * v[k] + 0.01 * double(g) * double(g);
      p[k] -= lr * double(g) / (std::sqrt(v[k]) + 1e-5);
    }
    opt.step(static_cast<float>(lr));
    CHECK(opt.steps() == t);
    for (int k = 0; k < 4; ++k) {
      INFO("step " << t << " param " << k);
      CHECK(w.value(k) == Approx(p[k]).epsilon(1e-6).margin(1e-7));
      CHECK(opt.square_avg()[0](k) == Approx(v[k]).epsilon(1e-5));
    }
    if (t == 1) {
      // v = 0.01 g^2 on the first step, so the step is lr * g / (0.1 |g|) = 10 lr.
      CHECK(w.value(0) == Approx(1.0 - 10 * lr).epsilon(1e-4));
    }
  }
}

TEST_CASE("clip_grad_norm matches torch.nn.utils.clip_grad_norm_", "[nn]") {
  ParamVector a(2, 0.0f), b(1, 0.0f);
  a.grad << 3.0f, 4.0f;
  b.grad << 12.0f;
  std::vector<ParamBlock> blocks = {a.block(), b.block()};
  CHECK(grad_norm(blocks) == Approx(13.0f));
  // Under the limit: untouched.
  CHECK(clip_grad_norm(blocks, 100.0f) == Approx(13.0f));
  CHECK(a.grad(0) == 3.0f);
  CHECK(b.grad(0) == 12.0f);
  // Over the limit: scaled by max_norm / (norm + 1e-6), norm before clipping returned.
  const float norm = clip_grad_norm(blocks, 0.5f);
  CHECK(norm == Approx(13.0f));
  const double coef = 0.5 / (13.0 + 1e-6);
  CHECK(a.grad(0) == Approx(3.0 * coef).epsilon(1e-6));
  CHECK(a.grad(1) == Approx(4.0 * coef).epsilon(1e-6));
  CHECK(b.grad(0) == Approx(12.0 * coef).epsilon(1e-6));
  CHECK(grad_norm(blocks) == Approx(0.5f).epsilon(1e-6));
  // Zero gradients stay zero.
  a.zero_grad();
  b.zero_grad();
  CHECK(clip_grad_norm(blocks, 0.5f) == 0.0f);
  CHECK(a.grad.isZero());
}

}  // namespace
}  // namespace rlrun
