#include "rlrun/nn/conv2d.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "rlrun/nn/dense_kernels.hpp"

namespace rlrun {

namespace {
using Index = std::ptrdiff_t;

// Copies a patch run of n floats. The runs are short (a CHW kernel row is 8 floats, an HWC one
// of a 2-frame stack 16): a call to memcpy for each was most of im2col's time, so whole
// 8-float blocks go by fixed-size copies the compiler inlines.
inline void copy_run(float* dst, const float* src, Index n) {
  constexpr Index kBlock = 8;
  Index t = 0;
  for (; t + kBlock <= n; t += kBlock) std::memcpy(dst + t, src + t, sizeof(float) * kBlock);
  for (; t < n; ++t) dst[t] = src[t];
}

// Calls run(input_offset, patch_offset, length) for every contiguous run of floats that patch p
// copies from the input: a kernel row of all channels (HWC) or of one channel (CHW).
template <class F>
void for_each_patch_run(const Conv2dShape& s, Index p, F&& run) {
  const Index oy = p / s.out_width(), ox = p % s.out_width();
  const Index y0 = oy * s.stride, x0 = ox * s.stride;
  if (s.channels_last) {
    const Index row = Index{s.kernel} * s.in_channels;
    for (int i = 0; i < s.kernel; ++i)
      run(((y0 + i) * s.in_width + x0) * s.in_channels, i * row, row);
    return;
  }
  for (int c = 0; c < s.in_channels; ++c) {
    for (int i = 0; i < s.kernel; ++i) {
      run((Index{c} * s.in_height + y0 + i) * s.in_width + x0, (Index{c} * s.kernel + i) * s.kernel,
          Index{s.kernel});
    }
  }
}
}  // namespace

void check_conv2d_shape(const Conv2dShape& s, const char* what) {
  if (s.in_channels <= 0 || s.in_height <= 0 || s.in_width <= 0 || s.out_channels <= 0 ||
      s.kernel <= 0 || s.stride <= 0) {
    throw std::invalid_argument(std::string(what) + ": sizes must be positive");
  }
  if (s.kernel > s.in_height || s.kernel > s.in_width) {
    throw std::invalid_argument(std::string(what) + ": a " + std::to_string(s.kernel) + "x" +
                                std::to_string(s.kernel) + " kernel does not fit a " +
                                std::to_string(s.in_height) + "x" + std::to_string(s.in_width) +
                                " input");
  }
}

void conv2d_im2col(const Conv2dShape& s, const float* input, float* patches) {
  const Index k = s.patch_size();
  for (Index p = 0; p < s.out_pixels(); ++p) {
    float* column = patches + p * k;
    for_each_patch_run(
        s, p, [&](Index in, Index at, Index length) { copy_run(column + at, input + in, length); });
  }
}

void conv2d_col2im(const Conv2dShape& s, const float* grad_patches, float* grad_input) {
  std::fill_n(grad_input, s.in_size(), 0.0f);
  const Index k = s.patch_size();
  // Patches in order, each run in order: the same sums in the same order on every CPU.
  for (Index p = 0; p < s.out_pixels(); ++p) {
    const float* column = grad_patches + p * k;
    for_each_patch_run(s, p, [&](Index in, Index at, Index length) {
      for (Index t = 0; t < length; ++t) grad_input[in + t] += column[at + t];
    });
  }
}

void conv2d_forward_relu(const Conv2dShape& s, const float* weight, const float* bias,
                         const float* input, float* patches, float* output) {
  conv2d_im2col(s, input, patches);
  dense::EpilogueArgs args;
  args.c = output;
  args.ldc = s.out_channels;
  args.bias = bias;
  const Index k = s.patch_size();
  dense::gemm_rows(s.out_channels, s.out_pixels(), k, weight, s.out_channels, patches, 1, k,
                   dense::Epilogue::kBiasReLU, args);
}

void conv2d_backward_relu(const Conv2dShape& s, const float* weight_t, const float* patches,
                          const float* output, float* grad_output, float* weight_grad,
                          float* bias_grad, float* grad_patches, float* grad_input) {
  const Index o = s.out_channels, p = s.out_pixels(), k = s.patch_size();
  // dL/dz = dL/dy where the ReLU passed its input (y > 0), else 0. A select, not a branch:
  // the compiler vectorizes it (the branch, taken at random, cost a fifth of NatureCNN's
  // forward and backward on CarRacing's 2x64x64 images).
  for (Index t = 0; t < o * p; ++t) grad_output[t] = output[t] > 0.0f ? grad_output[t] : 0.0f;
  dense::row_sum_add(o, p, grad_output, o, bias_grad);
  // dW (O x K) += dZ (O x P) * patches^T: B(q, kk) = patches(kk, q).
  dense::EpilogueArgs add;
  add.c = weight_grad;
  add.ldc = o;
  dense::gemm_rows(o, k, p, grad_output, o, patches, k, 1, dense::Epilogue::kAdd, add);
  if (grad_input == nullptr) return;
  // dPatches (K x P) = W^T (K x O) * dZ (O x P), then scattered back onto the input.
  dense::EpilogueArgs store;
  store.c = grad_patches;
  store.ldc = k;
  dense::gemm_rows(k, p, o, weight_t, k, grad_output, 1, o, dense::Epilogue::kStore, store);
  conv2d_col2im(s, grad_patches, grad_input);
}

}  // namespace rlrun
