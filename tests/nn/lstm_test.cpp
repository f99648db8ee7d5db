// nn/lstm: torch.nn.LSTM's equations with sb3-contrib's per-step resets, checked against a
// double-precision re-implementation written here from torch's documented formulas, and its
// backpropagation through time against central differences of that reference.
#include "rlrun/nn/lstm.hpp"

#include <catch2/catch.hpp>
#include <cmath>

#include "nn/grad_check.hpp"

namespace rlrun {
namespace {

using test::numeric_gradient;
using test::require_grad_close;

struct Sizes {
  int in, hidden, layers;
};

double sig(double x) { return 1.0 / (1.0 + std::exp(-x)); }

// torch.nn.LSTM in double from a parameter vector in Lstm::params()'s layout, time-major
// inputs (in x steps * n), with the state zeroed before every flagged step. Returns the last
// layer's outputs.
Eigen::MatrixXd reference_lstm(const Sizes& z, const Eigen::VectorXd& p, const Eigen::MatrixXd& x,
                               const Eigen::VectorXd& starts, Eigen::Index n,
                               const Eigen::MatrixXd& h0, const Eigen::MatrixXd& c0) {
  const int H = z.hidden;
  Eigen::MatrixXd input = x;
  Eigen::Index offset = 0;
  for (int k = 0; k < z.layers; ++k) {
    const int in = k == 0 ? z.in : H;
    Eigen::MatrixXd w_ih = Eigen::Map<const Eigen::MatrixXd>(p.data() + offset, 4 * H, in);
    offset += 4 * H * in;
    Eigen::MatrixXd w_hh = Eigen::Map<const Eigen::MatrixXd>(p.data() + offset, 4 * H, H);
    offset += 4 * H * H;
    Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(p.data() + offset, 4 * H);
    offset += 4 * H;
    b += Eigen::Map<const Eigen::VectorXd>(p.data() + offset, 4 * H);
    offset += 4 * H;
    Eigen::MatrixXd out(H, x.cols());
    for (Eigen::Index s = 0; s < n; ++s) {
      Eigen::VectorXd h = h0.block(k * H, s, H, 1), c = c0.block(k * H, s, H, 1);
      for (Eigen::Index t = 0; t * n < x.cols(); ++t) {
        const Eigen::Index col = t * n + s;
        if (starts(col) != 0.0) {
          h.setZero();
          c.setZero();
        }
        const Eigen::VectorXd a = w_ih * input.col(col) + w_hh * h + b;
        for (int j = 0; j < H; ++j) {
          const double i = sig(a(j)), f = sig(a(H + j)), g = std::tanh(a(2 * H + j)),
                       o = sig(a(3 * H + j));
          c(j) = f * c(j) + i * g;
          h(j) = o * std::tanh(c(j));
        }
        out.col(col) = h;
      }
    }
    input = out;
  }
  return input;
}

struct Case {
  Sizes sizes;
  Eigen::Index n, steps;
  Lstm lstm;
  Eigen::MatrixXf x;
  Eigen::RowVectorXf starts;
  Lstm::State initial;
};

Case make_case(Sizes z, Eigen::Index n, Eigen::Index steps, uint64_t seed) {
  Case k{z, n, steps, Lstm(z.in, z.hidden, z.layers), {}, {}, {}};
  Rng rng(seed);
  k.lstm.init_torch_default(rng);
  // Larger weights than torch's init so that the gates leave their linear range.
  k.lstm.params() *= 3.0f;
  k.x = Eigen::MatrixXf::NullaryExpr(z.in, n * steps, [&] { return float(rng.normal()); });
  k.starts = Eigen::RowVectorXf::Zero(n * steps);
  k.starts(0) = 1.0f;                      // sequence 0 starts an episode at step 0
  if (steps > 2) k.starts(2 * n + 1) = 1;  // sequence 1 resets mid-sequence
  k.initial = k.lstm.zero_state(n);
  k.initial.h.setRandom();
  k.initial.c.setRandom();
  return k;
}

TEST_CASE("Lstm forward equals torch's equations with resets, two layers", "[nn][lstm]") {
  Case k = make_case({3, 5, 2}, 3, 4, 7);
  Lstm::State state = k.initial;
  const Eigen::MatrixXf out = k.lstm.forward(k.x, k.starts, k.n, state);
  const Eigen::MatrixXd expected =
      reference_lstm(k.sizes, k.lstm.params().cast<double>(), k.x.cast<double>(),
                     k.starts.transpose().cast<double>(), k.n, k.initial.h.cast<double>(),
                     k.initial.c.cast<double>());
  REQUIRE(out.rows() == 5);
  REQUIRE(out.cols() == 12);
  CHECK((out.cast<double>() - expected).cwiseAbs().maxCoeff() < 1e-5);
  // The final state is the last step's (layer 1's h is the last output column of each sequence).
  for (Eigen::Index s = 0; s < k.n; ++s)
    CHECK((state.h.block(5, s, 5, 1) - out.col(3 * k.n + s)).cwiseAbs().maxCoeff() == 0.0f);
}

TEST_CASE("Lstm stepping one step at a time equals one forward over the sequence", "[nn][lstm]") {
  Case k = make_case({2, 4, 1}, 2, 5, 11);
  Lstm::State whole = k.initial, stepped = k.initial;
  const Eigen::MatrixXf out = k.lstm.forward(k.x, k.starts, k.n, whole);
  for (Eigen::Index t = 0; t < k.steps; ++t) {
    const Eigen::MatrixXf step =
        k.lstm.forward(k.x.middleCols(t * k.n, k.n), k.starts.segment(t * k.n, k.n), k.n, stepped);
    CHECK((step - out.middleCols(t * k.n, k.n)).cwiseAbs().maxCoeff() < 1e-6f);
  }
  CHECK((whole.h - stepped.h).cwiseAbs().maxCoeff() < 1e-6f);
  CHECK((whole.c - stepped.c).cwiseAbs().maxCoeff() < 1e-6f);
}

TEST_CASE("Lstm backward through time matches central differences", "[nn][lstm]") {
  Case k = make_case({3, 4, 2}, 2, 4, 3);
  // Loss = sum(w .* outputs) with fixed random weights w.
  Rng rng(5);
  const Eigen::MatrixXd w =
      Eigen::MatrixXd::NullaryExpr(4, k.n * k.steps, [&] { return rng.normal(); });
  const auto loss_of = [&](const Eigen::VectorXd& params, const Eigen::MatrixXd& x) {
    return (reference_lstm(k.sizes, params, x, k.starts.transpose().cast<double>(), k.n,
                           k.initial.h.cast<double>(), k.initial.c.cast<double>())
                .array() *
            w.array())
        .sum();
  };
  Lstm::State state = k.initial;
  k.lstm.forward(k.x, k.starts, k.n, state);
  k.lstm.zero_grad();
  Eigen::MatrixXf grad_x;
  k.lstm.backward(w.cast<float>(), &grad_x);

  const Eigen::MatrixXd x = k.x.cast<double>();
  const Eigen::VectorXd numeric_params = numeric_gradient(
      [&](const Eigen::VectorXd& p) { return loss_of(p, x); }, k.lstm.params().cast<double>());
  require_grad_close(k.lstm.grads().cast<double>(), numeric_params);
  const Eigen::VectorXd numeric_x = numeric_gradient(
      [&](const Eigen::VectorXd& flat) {
        return loss_of(k.lstm.params().cast<double>(),
                       Eigen::Map<const Eigen::MatrixXd>(flat.data(), x.rows(), x.cols()));
      },
      Eigen::Map<const Eigen::VectorXd>(x.data(), x.size()));
  require_grad_close(test::flat(grad_x), numeric_x);
}

TEST_CASE("Lstm saves and loads torch's state_dict names", "[nn][lstm]") {
  Case k = make_case({3, 4, 2}, 1, 1, 9);
  TensorMap tensors;
  k.lstm.save("lstm_actor", tensors);
  REQUIRE(tensors.size() == 8);
  CHECK(tensors.at("lstm_actor.weight_ih_l0").shape == std::vector<int64_t>{16, 3});
  CHECK(tensors.at("lstm_actor.weight_hh_l1").shape == std::vector<int64_t>{16, 4});
  CHECK(tensors.at("lstm_actor.bias_hh_l1").shape == std::vector<int64_t>{16});
  // Row-major (4H, in) as torch stores it: element (r, c) of W_ih.
  CHECK(tensors.at("lstm_actor.weight_ih_l0").data<float>()[1 * 3 + 2] ==
        k.lstm.weight_ih(0)(1, 2));
  Lstm other(3, 4, 2);
  other.load("lstm_actor", tensors);
  CHECK(other.params() == k.lstm.params());
  tensors.erase("lstm_actor.bias_ih_l1");
  CHECK_THROWS_WITH(other.load("lstm_actor", tensors), Catch::Contains("bias_ih_l1"));
}

}  // namespace
}  // namespace rlrun
