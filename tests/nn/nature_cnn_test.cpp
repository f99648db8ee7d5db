// Convolutions and SB3's NatureCNN (nn/conv2d.hpp, nn/nature_cnn.hpp) against a plain
// re-implementation in double with torch's semantics: Conv2d over a CHW image with torch's
// (O, C, kh, kw) weight, nn.Flatten's (C, H, W) order, the Linear layer, the ReLUs, and SB3's
// /255 and VecTransposeImage for channels-last images. The reference reads the network only
// through save() (torch's tensors), so it also checks the layout that SB3 model files use.
// Gradients are checked against central differences of that reference; results must not depend
// on the thread count or on the AVX2 / AVX-512 kernels.
#include <Eigen/Core>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "nn/nature_cnn_gradient_check.hpp"
#include "nn/nature_cnn_reference.hpp"
#include "rlrun/core/thread_pool.hpp"
#include "rlrun/nn/conv2d.hpp"
#include "rlrun/nn/dense_kernels.hpp"
#include "rlrun/nn/nature_cnn.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {
namespace {

using test::conv_relu;
using test::doubles;
using test::Image;
using test::reference_features;

Eigen::MatrixXf random_images(int dim, int batch, Rng& rng) {
  Eigen::MatrixXf x(dim, batch);
  for (Eigen::Index k = 0; k < x.size(); ++k)
    x.data()[k] = static_cast<float>(std::floor(rng.uniform(0.0, 256.0)));
  return x;
}

bool same_bits(const Eigen::MatrixXf& a, const Eigen::MatrixXf& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(float) * a.size()) == 0;
}

}  // namespace

TEST_CASE("conv2d: im2col forward and backward match a direct convolution", "[nn][cnn]") {
  for (bool channels_last : {true, false}) {
    INFO("channels_last " << channels_last);
    const Conv2dShape s{3, 11, 9, channels_last, 17, 3, 2};
    check_conv2d_shape(s, "test");
    Rng rng(5);
    std::vector<double> w(s.weight_size()), b(s.out_channels);
    for (double& v : w) v = rng.normal() * 0.3;
    for (double& v : b) v = rng.normal() * 0.1;
    std::vector<float> weight(s.weight_size()), bias(b.begin(), b.end());
    for (int o = 0; o < s.out_channels; ++o)
      for (int c = 0; c < s.in_channels; ++c)
        for (int i = 0; i < s.kernel; ++i)
          for (int j = 0; j < s.kernel; ++j)
            weight[o + s.patch_index(c, i, j) * s.out_channels] =
                static_cast<float>(w[s.torch_index(o, c, i, j)]);
    std::vector<float> input(s.in_size());
    for (float& v : input) v = static_cast<float>(rng.normal());
    Image x{s.in_channels, s.in_height, s.in_width, std::vector<double>(input.size())};
    for (int c = 0; c < s.in_channels; ++c)
      for (int y = 0; y < s.in_height; ++y)
        for (int xx = 0; xx < s.in_width; ++xx)
          x.at(c, y, xx) = input[channels_last ? (y * s.in_width + xx) * s.in_channels + c
                                               : (c * s.in_height + y) * s.in_width + xx];
    std::vector<double> wd(weight.size());
    for (size_t k = 0; k < w.size(); ++k) wd[k] = static_cast<float>(w[k]);
    const Image ref = conv_relu(x, wd, std::vector<double>(bias.begin(), bias.end()),
                                s.out_channels, s.kernel, s.stride);
    std::vector<float> patches(s.patch_size() * s.out_pixels()), out(s.out_size());
    conv2d_forward_relu(s, weight.data(), bias.data(), input.data(), patches.data(), out.data());
    for (int o = 0; o < s.out_channels; ++o)
      for (int p = 0; p < s.out_pixels(); ++p)
        REQUIRE(out[o + p * s.out_channels] ==
                Approx(ref.at(o, p / s.out_width(), p % s.out_width())).margin(1e-5));

    // Backward of L = sum(g * y) against central differences of the reference in double.
    std::vector<float> g(s.out_size());
    for (float& v : g) v = static_cast<float>(rng.normal());
    auto loss = [&](const Image& in, const std::vector<double>& weights,
                    const std::vector<double>& biases) {
      const Image y = conv_relu(in, weights, biases, s.out_channels, s.kernel, s.stride);
      double l = 0.0;
      for (int o = 0; o < s.out_channels; ++o)
        for (int p = 0; p < s.out_pixels(); ++p)
          l += g[o + p * s.out_channels] * y.at(o, p / s.out_width(), p % s.out_width());
      return l;
    };
    std::vector<float> weight_t(s.weight_size()), wgrad(s.weight_size(), 0.0f),
        bgrad(s.out_channels, 0.0f), grad_patches(patches.size()), grad_in(s.in_size());
    dense::transpose(s.out_channels, s.patch_size(), weight.data(), s.out_channels, weight_t.data(),
                     s.patch_size());
    std::vector<float> grad_out = g;
    conv2d_backward_relu(s, weight_t.data(), patches.data(), out.data(), grad_out.data(),
                         wgrad.data(), bgrad.data(), grad_patches.data(), grad_in.data());
    const std::vector<double> bd(bias.begin(), bias.end());
    const double h = 1e-6;
    for (int o = 0; o < s.out_channels; o += 4) {
      for (int c = 0; c < s.in_channels; ++c) {
        const int i = (o + c) % s.kernel, j = (o + 2 * c) % s.kernel;
        std::vector<double> wp = wd, wm = wd;
        wp[s.torch_index(o, c, i, j)] += h;
        wm[s.torch_index(o, c, i, j)] -= h;
        const double numeric = (loss(x, wp, bd) - loss(x, wm, bd)) / (2 * h);
        CHECK(wgrad[o + s.patch_index(c, i, j) * s.out_channels] == Approx(numeric).margin(1e-4));
      }
      std::vector<double> bp = bd, bm = bd;
      bp[o] += h;
      bm[o] -= h;
      CHECK(bgrad[o] == Approx((loss(x, wd, bp) - loss(x, wd, bm)) / (2 * h)).margin(1e-4));
    }
    for (int c = 0; c < s.in_channels; ++c)
      for (int y = 0; y < s.in_height; y += 2)
        for (int xx = 0; xx < s.in_width; xx += 3) {
          Image xp = x, xm = x;
          xp.at(c, y, xx) += h;
          xm.at(c, y, xx) -= h;
          const double numeric = (loss(xp, wd, bd) - loss(xm, wd, bd)) / (2 * h);
          CHECK(grad_in[channels_last ? (y * s.in_width + xx) * s.in_channels + c
                                      : (c * s.in_height + y) * s.in_width + xx] ==
                Approx(numeric).margin(1e-4));
        }
  }
}

TEST_CASE("NatureCNN computes SB3's features from torch's tensors, in either image layout",
          "[nn][cnn]") {
  for (bool channels_last : {true, false}) {
    INFO("channels_last " << channels_last);
    NatureCnn net({4, 84, 84, channels_last}, 512);
    CHECK(net.flatten_dim() == 3136);  // SB3's n_flatten for 84x84
    Rng rng(3);
    net.init_orthogonal(rng, std::sqrt(2.0f));
    const Eigen::MatrixXf x = random_images(net.in_dim(), 3, rng);
    const Eigen::MatrixXf features = net.forward(x);
    for (int s = 0; s < 3; ++s) {
      const Eigen::VectorXd ref = reference_features(net, x.col(s));
      for (int o = 0; o < 512; ++o) REQUIRE(features(o, s) == Approx(ref(o)).margin(2e-5));
    }
  }
}

TEST_CASE("NatureCNN's init follows torch's shapes and laws", "[nn][cnn]") {
  NatureCnn net({3, 64, 64, true}, 256);
  Rng rng(1);
  net.init_orthogonal(rng, std::sqrt(2.0f));
  TensorMap t;
  net.save("features_extractor", t);
  REQUIRE(t.at("features_extractor.cnn.0.weight").shape == std::vector<int64_t>{32, 3, 8, 8});
  REQUIRE(t.at("features_extractor.cnn.4.weight").shape == std::vector<int64_t>{64, 64, 3, 3});
  REQUIRE(t.at("features_extractor.linear.0.weight").shape == std::vector<int64_t>{256, 1024});
  // orthogonal_ flattens a conv weight to (O, C*k*k): its rows are orthonormal times the gain.
  const Tensor& w0 = t.at("features_extractor.cnn.0.weight");
  using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const Eigen::Map<const RowMajor> m(w0.data<float>(), 32, 192);
  const Eigen::MatrixXf gram = m * m.transpose();
  CHECK((gram - 2.0f * Eigen::MatrixXf::Identity(32, 32)).cwiseAbs().maxCoeff() < 1e-4f);
  CHECK(Eigen::Map<const Eigen::VectorXf>(t.at("features_extractor.cnn.0.bias").data<float>(), 32)
            .isZero());
  // torch's default: U(-1/sqrt(fan_in), 1/sqrt(fan_in)) on weights and biases.
  NatureCnn plain({3, 64, 64, true}, 256);
  plain.init_torch_default(rng);
  TensorMap u;
  plain.save("fe", u);
  const Tensor& lw = u.at("fe.linear.0.weight");
  const float bound = 1.0f / std::sqrt(1024.0f);
  const Eigen::Map<const Eigen::VectorXf> values(lw.data<float>(), lw.numel());
  CHECK(values.cwiseAbs().maxCoeff() <= bound);
  CHECK(values.cwiseAbs().maxCoeff() > 0.99f * bound);
  CHECK(std::abs(values.mean()) < 0.01f * bound);
}

TEST_CASE("NatureCNN's gradients match central differences", "[nn][cnn]") {
  // A small network (36x36, the smallest NatureCNN fits) keeps the differences quick.
  for (bool channels_last : {true, false}) {
    INFO("channels_last " << channels_last);
    NatureCnn net({2, 37, 36, channels_last}, 16);
    Rng rng(9);
    net.init_torch_default(rng);
    const int batch = 3;
    const Eigen::MatrixXf x = random_images(net.in_dim(), batch, rng);
    Eigen::MatrixXf g(16, batch);
    for (Eigen::Index k = 0; k < g.size(); ++k) g.data()[k] = static_cast<float>(rng.normal());
    net.forward(x);
    net.zero_grad();
    net.backward(g);
    auto loss = [&](const NatureCnn& n) {
      double l = 0.0;
      for (int s = 0; s < batch; ++s)
        l += g.col(s).cast<double>().dot(reference_features(n, x.col(s)));
      return l;
    };
    // Parameters spread over every layer.
    CHECK(test::check_cnn_gradient(net, loss, "NatureCNN", 97, 1e-4, 1e-3) > 90);
  }
}

TEST_CASE("NatureCNN gives the same bits for every thread count and kernel path", "[nn][cnn]") {
  NatureCnn net({4, 84, 84, false}, 512);
  Rng rng(4);
  net.init_orthogonal(rng, std::sqrt(2.0f));
  const Eigen::MatrixXf x = random_images(net.in_dim(), 40, rng);
  Eigen::MatrixXf g(512, 40);
  for (Eigen::Index k = 0; k < g.size(); ++k) g.data()[k] = static_cast<float>(rng.normal());
  auto run = [&](ThreadPool* pool) {
    NatureCnn copy = net;
    copy.set_thread_pool(pool);
    const Eigen::MatrixXf features = copy.forward(x);
    copy.backward(g);
    return std::make_pair(features, Eigen::MatrixXf(copy.grads()));
  };
  const auto one = run(nullptr);
  for (int threads : {2, 3}) {
    ThreadPool pool(threads);
    const auto many = run(&pool);
    CHECK(same_bits(one.first, many.first));
    CHECK(same_bits(one.second, many.second));
  }
  if (!dense::kernel_path_available(dense::KernelPath::kAvx512)) {
    WARN("no AVX-512 here: NatureCNN's AVX-512 and AVX2 bits were not compared");
    return;
  }
  dense::select_kernels("avx2");
  const auto avx2 = run(nullptr);
  dense::select_kernels("avx512");
  const auto avx512 = run(nullptr);
  dense::select_kernels("auto");
  CHECK(same_bits(avx2.first, avx512.first));
  CHECK(same_bits(avx2.second, avx512.second));
}

TEST_CASE("NatureCNN saves and loads torch's tensors and refuses others", "[nn][cnn]") {
  NatureCnn net({1, 40, 50, true}, 32);
  Rng rng(2);
  net.init_torch_default(rng);
  TensorMap t;
  net.save("q_net.features_extractor", t);
  NatureCnn other({1, 40, 50, true}, 32);
  other.load("q_net.features_extractor", t);
  CHECK(same_bits(Eigen::MatrixXf(net.params()), Eigen::MatrixXf(other.params())));
  TensorMap wrong = t;
  wrong["q_net.features_extractor.cnn.2.weight"].shape = {64, 32, 2, 8};
  CHECK_THROWS_WITH(other.load("q_net.features_extractor", wrong),
                    Catch::Contains("cnn.2.weight") && Catch::Contains("different shape"));
  TensorMap missing = t;
  missing.erase("q_net.features_extractor.linear.0.bias");
  CHECK_THROWS_WITH(other.load("q_net.features_extractor", missing),
                    Catch::Contains("no tensor 'q_net.features_extractor.linear.0.bias'"));
  CHECK_THROWS_WITH(NatureCnn({3, 35, 84, true}), Catch::Contains("at least 36x36"));
}

}  // namespace rlrun
