// Micro-benchmark of Mlp forward + backward. Hidden (and not tagged [nn], which would select it):
// run with `rlrun_tests "[nn_bench]"`.
// Prints throughput; asserts nothing about time (DESIGN.md §8). FLOPs are counted as
// 2 * in * out * batch per layer forward and twice that backward (weight and input gradients),
// the usual 3x-forward convention.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include <catch2/catch.hpp>

#include "rlrun/core/rng.hpp"
#include "rlrun/nn/mlp.hpp"

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
  std::printf("%d %s batch %4d: fwd+bwd %8.2f us  %10.0f samples/s  %6.1f GFLOP/s | fwd %7.2f us "
              "%6.1f GFLOP/s\n",
              out, std::string(activation_name(act)).c_str(), batch, best * 1e6, batch / best,
              flops / best * 1e-9, best_fwd * 1e6, flops_fwd / best_fwd * 1e-9);
  CHECK(net.output().allFinite());
}

TEST_CASE("Mlp forward+backward micro-benchmark", "[.bench][nn_bench]") {
  bench(4, {64, 64}, 2, Activation::kTanh, 256);
  bench(4, {64, 64}, 2, Activation::kTanh, 64);
  bench(4, {64, 64}, 1, Activation::kTanh, 256);
  bench(4, {64, 64}, 2, Activation::kTanh, 1);
  bench(4, {64, 64}, 2, Activation::kTanh, 8);
  bench(17, {256, 256}, 6, Activation::kReLU, 256);
  bench(4, {64, 64}, 2, Activation::kReLU, 256);
}

}  // namespace
}  // namespace rlrun
