// The two-core split of a training step (nn/batch_split.hpp, split_mlp.*, split_adam.*): a
// SplitMlp's passes over a minibatch are exactly those of two plain Mlps on its halves with the
// second half's gradient added last, close to one pass over the whole batch, and the same bits
// with no pool and with pools of 1, 2, 3 and 8 threads; a SplitAdam is one Adam over the whole
// vector.
#include "rlrun/nn/split_mlp.hpp"

#include <catch2/catch.hpp>
#include <vector>

#include "rlrun/nn/batch_split.hpp"
#include "rlrun/nn/split_adam.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {
namespace {

Eigen::MatrixXf random_matrix(Eigen::Index rows, Eigen::Index cols, Rng& rng) {
  Eigen::MatrixXf m(rows, cols);
  for (Eigen::Index k = 0; k < m.size(); ++k) m(k) = static_cast<float>(rng.normal());
  return m;
}

struct Passes {
  Eigen::MatrixXf output, grad_input;
  Eigen::VectorXf grads;
};

// forward, backward (twice: gradients add up) and backward_input through a SplitMlp.
Passes split_passes(const Mlp& net, ThreadPool* pool, const Eigen::MatrixXf& x,
                    const Eigen::MatrixXf& grad_out) {
  SplitMlp split(net, pool);
  Passes p;
  p.output = split.forward(x);
  CHECK(split.output() == p.output);
  split.zero_grad();
  split.backward(grad_out);
  split.backward(grad_out);
  p.grads = split.grads();
  split.backward_input(grad_out, p.grad_input, 2);
  CHECK(split.grads() == p.grads);  // input gradient only
  // zero_grad_and_backward is zero_grad, then backward.
  SplitMlp other(net, pool);
  other.forward(x);
  other.zero_grad();
  other.backward(grad_out);
  split.zero_grad_and_backward(grad_out);
  CHECK(split.grads() == other.grads());
  return p;
}

// The same passes through plain Mlps: the whole batch in one, or its parts in one Mlp each,
// where each backward adds the further parts' gradients (each computed from zero) to the
// first's, in part order.
Passes halves_passes(const Mlp& net, const Eigen::MatrixXf& x, const Eigen::MatrixXf& grad_out,
                     bool halves) {
  const Eigen::Index n = x.cols();
  const int parts = halves ? column_parts(n, net.multiply_adds_per_column()) : 1;
  const auto cols = [&](int k) { return column_part(n, parts, k); };
  Passes p;
  p.output.resize(net.out_dim(), n);
  p.grad_input.resize(net.in_dim() - 2, n);
  std::vector<Mlp> nets(static_cast<size_t>(parts), net);
  Mlp& first = nets.front();
  for (int k = 0; k < parts; ++k)
    p.output.middleCols(cols(k).begin, cols(k).count) =
        nets[k].forward(x.middleCols(cols(k).begin, cols(k).count));
  first.zero_grad();
  for (int pass = 0; pass < 2; ++pass) {
    first.backward(grad_out.middleCols(cols(0).begin, cols(0).count));
    for (int k = 1; k < parts; ++k) {
      nets[k].zero_grad();
      nets[k].backward(grad_out.middleCols(cols(k).begin, cols(k).count));
    }
    for (int k = 1; k < parts; ++k) first.grads() += nets[k].grads();
  }
  p.grads = first.grads();
  for (int k = 0; k < parts; ++k) {
    Eigen::MatrixXf gi;
    nets[k].backward_input(grad_out.middleCols(cols(k).begin, cols(k).count), gi, 2);
    p.grad_input.middleCols(cols(k).begin, cols(k).count) = gi;
  }
  return p;
}

}  // namespace

TEST_CASE(
    "Minibatch columns split in halves from 32 on when the pass is large enough, parameters on a "
    "cache line",
    "[nn][split]") {
  const Eigen::Index big = 100000, small = 4416;  // 256x256 vs RLtools' 64x64 SAC critic
  CHECK(column_parts(31, big) == 1);
  CHECK(column_part(31, 1, 0).count == 31);
  CHECK(column_parts(32, big) == 2);
  CHECK(column_parts(100, small) == 1);  // 0.44 M multiply-adds: not worth a hand-off
  CHECK(column_parts(400, small) == 2);
  CHECK(column_part(37, 2, 0).count == 18);
  CHECK(column_part(37, 2, 1).begin == 18);
  CHECK(column_part(37, 2, 1).count == 19);
  CHECK(param_part(1000, 0).count == 496);
  CHECK(param_part(1000, 1).begin == 496);
  CHECK(param_part(1000, 1).count == 504);
  CHECK(param_part(10, 0).count == 0);
  // Beyond two: parts of at least 128 columns and 4 M multiply-adds each, at most 16.
  CHECK(column_parts(256, 67000) == 2);   // rl-zoo SAC critics at batch 256
  CHECK(column_parts(512, 540000) == 4);  // TQC's 512x512x512 critics at batch 512
  CHECK(column_parts(1024, 540000) == 8);
  CHECK(column_parts(1 << 20, 540000) == 16);
  CHECK(column_parts(4096, 4416) == 4);     // small networks: bounded by the work
  CHECK(column_part(10, 4, 0).count == 2);  // [0, 2) [2, 5) [5, 7) [7, 10)
  CHECK(column_part(10, 4, 1).begin == 2);
  CHECK(column_part(10, 4, 2).begin == 5);
  CHECK(column_part(10, 4, 3).count == 3);
}

TEST_CASE(
    "SplitMlp passes equal two plain Mlps on the halves, with or without the second core, and "
    "are close to one pass over the whole batch",
    "[nn][split]") {
  const int n = GENERATE(5, 37, 64, 600);
  // 6 inputs: the input gradient (rows 2..5) by dot products; 40: through the transposed first
  // weight, which the halves share (SplitMlp::transpose_for_halves), as they share the hidden
  // layers' (300 and 200 rows: W^T split between the cores off a 16-float boundary too). 7: a
  // GELU network, whose parts keep their own pre-activations for the backward.
  const int in_dim = GENERATE(6, 40, 7);
  INFO("batch " << n << ", " << in_dim << " inputs");
  Rng rng(3);
  // 67 k, 76 k and 68 k multiply-adds a column: 37 columns split.
  Mlp net = in_dim == 6    ? Mlp(6, {256, 256}, 3, Activation::kReLU)
            : in_dim == 40 ? Mlp(40, {300, 200}, 20, Activation::kTanh)
                           : Mlp(7, {256, 256}, 2, Activation::kGELU);
  net.init_torch_default(rng);
  REQUIRE(column_parts(n, net.multiply_adds_per_column()) == (n >= 512 ? 4 : n >= 32 ? 2 : 1));
  const Eigen::MatrixXf x = random_matrix(in_dim, n, rng);
  const Eigen::MatrixXf grad_out = random_matrix(net.out_dim(), n, rng);

  const Passes one = split_passes(net, nullptr, x, grad_out);
  for (const int threads : {1, 2, 3, 8}) {
    INFO(threads << " threads");
    ThreadPool pool(threads);
    const Passes pooled = split_passes(net, &pool, x, grad_out);
    CHECK(one.output == pooled.output);
    CHECK(one.grads == pooled.grads);
    CHECK(one.grad_input == pooled.grad_input);
  }

  const Passes halves = halves_passes(net, x, grad_out, true);
  CHECK(one.output == halves.output);
  CHECK(one.grads == halves.grads);
  CHECK(one.grad_input == halves.grad_input);

  const Passes whole = halves_passes(net, x, grad_out, false);
  CHECK(one.output == whole.output);  // column by column, the same products
  CHECK(one.grad_input == whole.grad_input);
  CHECK((one.grads - whole.grads).cwiseAbs().maxCoeff() <=
        1e-5f * whole.grads.cwiseAbs().maxCoeff());
}

TEST_CASE("SplitMlp reads its parameters in place: no copy to refresh after a change",
          "[nn][split]") {
  Rng rng(4);
  SplitMlp split(5, {1024, 1024}, 2, Activation::kTanh);  // large enough to split 40 columns
  split.net().init_torch_default(rng);
  const Eigen::MatrixXf x = random_matrix(5, 40, rng);
  REQUIRE(column_parts(40, split.net().multiply_adds_per_column()) == 2);
  split.forward(x);
  split.params() *= 0.5f;  // e.g. an optimizer step
  Mlp plain = split.net();
  CHECK(split.forward(x) == halves_passes(plain, x, Eigen::MatrixXf::Zero(2, 40), true).output);
  // Copies (acting networks) are independent networks with the same parameters.
  SplitMlp copy = split;
  copy.params().setZero();
  CHECK(split.params() == plain.params());
}

TEST_CASE("SplitAdam is one Adam over the whole vector, its norm is the gradient's",
          "[nn][split]") {
  Rng rng(5);
  const int size = 1000;  // parts of 496 and 504
  Eigen::VectorXf p_split = random_matrix(size, 1, rng), g_split(size);
  Eigen::VectorXf p_one = p_split, g_one(size);
  ThreadPool pool(2);
  SplitAdam split({p_split.data(), g_split.data(), size}, {}, &pool);
  Adam one({{p_one.data(), g_one.data(), size}});
  for (int step = 0; step < 5; ++step) {
    g_split = random_matrix(size, 1, rng);
    g_one = g_split;
    CHECK(split.grad_norm() == Approx(g_one.cast<double>().norm()).epsilon(1e-6));
    split.step(1e-3f, 0.5f);
    g_one *= 0.5f;
    one.step(1e-3f);
    CHECK(p_split == p_one);
  }
  CHECK(split.part(0).steps() == 5);
  CHECK(split.part(1).exp_avg()[0].size() == 504);
}

}  // namespace rlrun
