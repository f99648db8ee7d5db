#pragma once
// SB3's NatureCNN re-implemented in double with torch's semantics, reading a network only
// through NatureCnn::save (torch's tensors): VecTransposeImage for channels-last images,
// preprocess_obs's /255, Conv2d + ReLU three times, nn.Flatten's (C, H, W) order, Linear + ReLU.
// The reference the CNN's own tests and the algorithms' CnnPolicy tests differentiate.
#include <Eigen/Core>
#include <algorithm>
#include <string>
#include <vector>

#include "rlrun/nn/nature_cnn.hpp"

namespace rlrun::test {

// A CHW image in double: c * h * w values.
struct Image {
  int c = 0, h = 0, w = 0;
  std::vector<double> v;
  double& at(int ch, int y, int x) { return v[(static_cast<size_t>(ch) * h + y) * w + x]; }
  double at(int ch, int y, int x) const { return v[(static_cast<size_t>(ch) * h + y) * w + x]; }
};

// torch.nn.functional.conv2d(x, weight, bias, stride) followed by relu, weight (O, C, k, k)
// row-major.
inline Image conv_relu(const Image& x, const std::vector<double>& weight,
                       const std::vector<double>& bias, int out, int k, int stride) {
  Image y{out, (x.h - k) / stride + 1, (x.w - k) / stride + 1, {}};
  y.v.assign(static_cast<size_t>(y.c) * y.h * y.w, 0.0);
  for (int o = 0; o < out; ++o)
    for (int oy = 0; oy < y.h; ++oy)
      for (int ox = 0; ox < y.w; ++ox) {
        double s = bias[o];
        for (int c = 0; c < x.c; ++c)
          for (int i = 0; i < k; ++i)
            for (int j = 0; j < k; ++j)
              s += weight[((static_cast<size_t>(o) * x.c + c) * k + i) * k + j] *
                   x.at(c, oy * stride + i, ox * stride + j);
        y.at(o, oy, ox) = std::max(s, 0.0);
      }
  return y;
}

inline std::vector<double> doubles(const Tensor& t) {
  const float* f = t.data<float>();
  return std::vector<double>(f, f + t.numel());
}

// SB3: VecTransposeImage (HWC -> CHW when channels-last), preprocess_obs (/255), NatureCNN.
inline Eigen::VectorXd reference_features(const NatureCnn& net, const Eigen::VectorXf& obs) {
  TensorMap t;
  net.save("fe", t);
  const ImageInput& in = net.input();
  Image x{in.channels, in.height, in.width, std::vector<double>(obs.size())};
  for (int c = 0; c < in.channels; ++c)
    for (int y = 0; y < in.height; ++y)
      for (int xx = 0; xx < in.width; ++xx) {
        const Eigen::Index at = in.channels_last
                                    ? (Eigen::Index{y} * in.width + xx) * in.channels + c
                                    : (Eigen::Index{c} * in.height + y) * in.width + xx;
        x.at(c, y, xx) = net.normalize_images() ? obs(at) / 255.0 : obs(at);
      }
  const int spec[3][3] = {{32, 8, 4}, {64, 4, 2}, {64, 3, 1}};
  for (int l = 0; l < 3; ++l) {
    const std::string name = "fe.cnn." + std::to_string(2 * l);
    x = conv_relu(x, doubles(t.at(name + ".weight")), doubles(t.at(name + ".bias")), spec[l][0],
                  spec[l][1], spec[l][2]);
  }
  const std::vector<double> w = doubles(t.at("fe.linear.0.weight")),
                            b = doubles(t.at("fe.linear.0.bias"));
  const int f = net.features_dim(), flat = static_cast<int>(x.v.size());
  Eigen::VectorXd out(f);
  for (int o = 0; o < f; ++o) {
    double s = b[o];
    for (int q = 0; q < flat; ++q) s += w[static_cast<size_t>(o) * flat + q] * x.v[q];
    out(o) = std::max(s, 0.0);
  }
  return out;
}

}  // namespace rlrun::test
