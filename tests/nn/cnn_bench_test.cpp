// Micro-benchmark of NatureCNN forward + backward (nn/nature_cnn.hpp) on SB3's Atari-sized
// input, 4x84x84, batch 256 and the acting batch of 8, and on the zoo's CarRacing input.
// Hidden: run with `rlrun_tests "[cnn_bench]"` (RLRUN_THREADS=1 for one core). Prints throughput; asserts
// nothing about time (docs/benchmarks.md). FLOPs counted exactly: 2 per multiply-add forward;
// backward the weight gradients (as many) plus the input gradients of every layer but the first
// (an image has no gradient).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <catch2/catch.hpp>

#include "rlrun/nn/nature_cnn.hpp"
#include "rlrun/rng.hpp"
#include "test_threads.hpp"

namespace rlrun {
namespace {

void bench(int batch, ThreadPool* pool, ImageInput image = {4, 84, 84, false}) {
  NatureCnn net(image, 512);
  Rng rng(1);
  net.init_orthogonal(rng, std::sqrt(2.0f));
  net.set_thread_pool(pool);
  Eigen::MatrixXf x(net.in_dim(), batch), g(512, batch);
  for (Eigen::Index k = 0; k < x.size(); ++k) x(k) = static_cast<float>(rng.uniform(0.0, 255.0));
  for (Eigen::Index k = 0; k < g.size(); ++k) g(k) = static_cast<float>(rng.normal());
  const double forward = 2.0 * static_cast<double>(net.multiply_adds_per_column()) * batch;
  const double first = 2.0 * static_cast<double>(net.conv(0).multiply_adds()) * batch;
  const double total = forward + forward + (forward - first);
  net.forward(x);
  net.backward(g);
  const int iters = std::max(3, static_cast<int>(2e9 / total));
  double best = 1e30, best_fwd = 1e30;
  for (int rep = 0; rep < 3; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < iters; ++i) {
      net.forward(x);
      net.backward(g);
    }
    const auto t1 = std::chrono::steady_clock::now();
    for (int i = 0; i < iters; ++i) net.forward(x);
    const auto t2 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double>(t1 - t0).count() / iters);
    best_fwd = std::min(best_fwd, std::chrono::duration<double>(t2 - t1).count() / iters);
  }
  std::printf(
      "NatureCNN %dx%dx%d batch %3d, %d thread(s): fwd+bwd %8.2f ms %6.1f GFLOP/s | fwd %7.2f ms "
      "%6.1f GFLOP/s\n",
      image.channels, image.height, image.width, batch, pool ? pool->threads() : 1, best * 1e3,
      total / best * 1e-9, best_fwd * 1e3, forward / best_fwd * 1e-9);
  CHECK(net.output().allFinite());
}

}  // namespace

TEST_CASE("NatureCNN forward+backward micro-benchmark", "[.bench][cnn_bench]") {
  bench(256, nullptr);
  bench(8, nullptr);
  bench(256, &testing::test_thread_pool());
  // The zoo's CarRacing entry: 64x64 gray, 2 frames stacked channels-last, minibatch 128.
  bench(128, nullptr, {2, 64, 64, true});
}

}  // namespace rlrun
