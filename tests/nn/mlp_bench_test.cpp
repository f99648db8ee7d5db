// Micro-benchmark of Mlp forward + backward. Hidden (and not tagged [nn], which would select it):
// run with `rlrun_tests "[nn_bench]"`.
// Prints throughput; asserts nothing about time (docs/benchmarks.md). FLOPs are counted as
// 2 * in * out * batch per layer forward and twice that backward (weight and input gradients),
// the usual 3x-forward convention.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "rlrun/nn/mlp.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {
namespace {

void bench(int in, std::vector<int> hidden, int out, Activation act, int batch) {
  Rng rng(1);
  Mlp net(in, hidden, out, act);
  net.init_orthogonal(rng, std::sqrt(2.0f), 1.0f);
  Eigen::MatrixXf x(in, batch), g(out, batch);
  for (Eigen::Index k = 0; k < x.size(); ++k) x(k) = static_cast<float>(rng.normal());
  for (Eigen::Index k = 0; k < g.size(); ++k) g(k) = static_cast<float>(rng.normal());
  double flops_fwd = 0.0;
  for (int l = 0; l < net.num_layers(); ++l) {
    flops_fwd += 2.0 * net.layer_in(l) * net.layer_out(l) * batch;
  }
  const double flops = 3.0 * flops_fwd;
  // Warm up, then pick an iteration count worth ~0.3 s, keep the best of 5 runs.
  for (int i = 0; i < 50; ++i) {
    net.forward(x);
    net.backward(g);
  }
  const int iters = std::max(10, static_cast<int>(0.06e9 / flops * 10));
  double best = 1e30;
  double best_fwd = 1e30;
  for (int rep = 0; rep < 5; ++rep) {
    auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < iters; ++i) {
      net.forward(x);
      net.backward(g);
    }
    auto t1 = std::chrono::steady_clock::now();
    for (int i = 0; i < iters; ++i) net.forward(x);
    auto t2 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double>(t1 - t0).count() / iters);
    best_fwd = std::min(best_fwd, std::chrono::duration<double>(t2 - t1).count() / iters);
  }
  std::printf("mlp %d-", in);
  for (int h : hidden) std::printf("%d-", h);
  std::printf(
      "%d %s batch %4d: fwd+bwd %8.2f us  %10.0f samples/s  %6.1f GFLOP/s | fwd %7.2f us "
      "%6.1f GFLOP/s\n",
      out, std::string(activation_name(act)).c_str(), batch, best * 1e6, batch / best,
      flops / best * 1e-9, best_fwd * 1e6, flops_fwd / best_fwd * 1e-9);
  CHECK(net.output().allFinite());
}

// The same 4-64-64-2 tanh step written as plain Eigen (noalias products, separate bias/tanh
// passes), the baseline the kernels are measured against.
void bench_plain_eigen(int batch) {
  Rng rng(1);
  const int in = 4, h = 64, out = 2;
  Eigen::MatrixXf w1 = Eigen::MatrixXf::Random(h, in), w2 = Eigen::MatrixXf::Random(h, h);
  Eigen::MatrixXf w3 = Eigen::MatrixXf::Random(out, h);
  Eigen::VectorXf b1 = Eigen::VectorXf::Random(h), b2 = Eigen::VectorXf::Random(h);
  Eigen::VectorXf b3 = Eigen::VectorXf::Random(out);
  Eigen::MatrixXf gw1 = w1, gw2 = w2, gw3 = w3;
  Eigen::VectorXf gb1 = b1, gb2 = b2, gb3 = b3;
  Eigen::MatrixXf x = Eigen::MatrixXf::Random(in, batch), g = Eigen::MatrixXf::Random(out, batch);
  Eigen::MatrixXf a1(h, batch), a2(h, batch), y(out, batch), d2(h, batch), d1(h, batch);
  const auto step = [&] {
    a1.noalias() = w1 * x;
    a1.colwise() += b1;
    a1.array() = a1.array().tanh();
    a2.noalias() = w2 * a1;
    a2.colwise() += b2;
    a2.array() = a2.array().tanh();
    y.noalias() = w3 * a2;
    y.colwise() += b3;
    gw3.noalias() += g * a2.transpose();
    gb3 += g.rowwise().sum();
    d2.noalias() = w3.transpose() * g;
    d2.array() *= 1.0f - a2.array().square();
    gw2.noalias() += d2 * a1.transpose();
    gb2 += d2.rowwise().sum();
    d1.noalias() = w2.transpose() * d2;
    d1.array() *= 1.0f - a1.array().square();
    gw1.noalias() += d1 * x.transpose();
    gb1 += d1.rowwise().sum();
  };
  for (int i = 0; i < 50; ++i) step();
  const double flops = 3.0 * 2.0 * (in * h + h * h + h * out) * batch;
  const int iters = std::max(10, static_cast<int>(0.06e9 / flops * 10));
  double best = 1e30;
  for (int rep = 0; rep < 5; ++rep) {
    auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < iters; ++i) step();
    auto t1 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double>(t1 - t0).count() / iters);
  }
  std::printf(
      "plain Eigen 4-64-64-2 tanh batch %4d: fwd+bwd %8.2f us  %10.0f samples/s  %6.1f "
      "GFLOP/s\n",
      batch, best * 1e6, batch / best, flops / best * 1e-9);
  CHECK(gw1.allFinite());
}

TEST_CASE("Mlp forward+backward micro-benchmark", "[.bench][nn_bench]") {
  bench_plain_eigen(256);
  bench_plain_eigen(64);
  bench(4, {64, 64}, 2, Activation::kTanh, 256);
  bench(4, {64, 64}, 2, Activation::kTanh, 64);
  bench(4, {64, 64}, 1, Activation::kTanh, 256);
  bench(4, {64, 64}, 2, Activation::kTanh, 1);
  bench(4, {64, 64}, 2, Activation::kTanh, 8);
  bench(17, {256, 256}, 6, Activation::kReLU, 256);
  bench(4, {64, 64}, 2, Activation::kReLU, 256);
  // Off-policy critics at rl-zoo Pendulum sizes on one core's half of a batch of 256 (SAC
  // 256x256, TD3/DDPG 400x300: widths that are not a multiple of the packet).
  bench(4, {256, 256}, 1, Activation::kReLU, 128);
  bench(4, {400, 300}, 1, Activation::kReLU, 128);
  // The other activations at the same sizes (ELU's expm1 costs more than tanh's rational).
  bench(4, {64, 64}, 2, Activation::kELU, 256);
  bench(4, {64, 64}, 2, Activation::kLeakyReLU, 256);
  bench(4, {256, 256}, 1, Activation::kLeakyReLU, 128);
}

}  // namespace
}  // namespace rlrun
