#pragma once
// One torch.nn.Conv2d layer without padding or dilation (what SB3's NatureCNN uses:
// common/torch_layers.py), as per-sample kernels on top of the dense GEMMs
// (dense_kernels.hpp), so a convolution gets the same runtime dispatch and the same bits on
// AVX2 and AVX-512 as every dense layer.
//
// The method is im2col (Chellapilla et al. 2006, "High performance convolutional neural
// networks for document processing"): the input patch under each output pixel is copied into
// a column of a K x P matrix (K = channels * kernel^2 inputs per patch, P output pixels), and
// the layer becomes one product W (O x K) * patches (K x P).
//
// Layouts (all column-major float, one sample at a time):
//  * input: an image of in_channels x in_height x in_width, channels-last (HWC, Gymnasium's
//    image layout: float (y * width + x) * channels + c) or channels-first (CHW, torch's:
//    (c * height + y) * width + x);
//  * output: always channels-last, i.e. an O x P matrix (column p = y * out_width + x holds the
//    O channels of that pixel), which is the next layer's HWC input as it is;
//  * weight: O x K column-major, the patch index k in the order the input lays its floats out:
//    (row, column, channel) for an HWC input, (channel, row, column) — torch's own order — for
//    a CHW one. torch_index() maps between this and torch's (O, C, kh, kw) row-major weight,
//    for saving, loading and export.
#include <cstddef>

namespace rlrun {

struct Conv2dShape {
  int in_channels = 1, in_height = 1, in_width = 1;
  bool channels_last = true;  // the input's layout (the output is always channels-last)
  int out_channels = 1, kernel = 1, stride = 1;

  int out_height() const { return (in_height - kernel) / stride + 1; }
  int out_width() const { return (in_width - kernel) / stride + 1; }
  // Floats of one input patch (K) and output pixels (P).
  std::ptrdiff_t patch_size() const {
    return static_cast<std::ptrdiff_t>(in_channels) * kernel * kernel;
  }
  std::ptrdiff_t out_pixels() const {
    return static_cast<std::ptrdiff_t>(out_height()) * out_width();
  }
  std::ptrdiff_t in_size() const {
    return static_cast<std::ptrdiff_t>(in_channels) * in_height * in_width;
  }
  std::ptrdiff_t out_size() const { return out_pixels() * out_channels; }
  std::ptrdiff_t weight_size() const { return patch_size() * out_channels; }
  // Multiply-adds of one sample's forward pass.
  std::ptrdiff_t multiply_adds() const { return weight_size() * out_pixels(); }
  // The patch index k (this layer's weight column) of torch's weight[o][c][i][j].
  std::ptrdiff_t patch_index(int c, int i, int j) const {
    return channels_last ? (static_cast<std::ptrdiff_t>(i) * kernel + j) * in_channels + c
                         : (static_cast<std::ptrdiff_t>(c) * kernel + i) * kernel + j;
  }
  // Offset of weight (o, k = patch_index(c, i, j)) in torch's (O, C, kh, kw) row-major weight.
  std::ptrdiff_t torch_index(int o, int c, int i, int j) const {
    return ((static_cast<std::ptrdiff_t>(o) * in_channels + c) * kernel + i) * kernel + j;
  }
};

// Throws std::invalid_argument (naming `what`) unless every size is positive and the kernel
// fits in the input.
void check_conv2d_shape(const Conv2dShape& shape, const char* what);

// patches (K x P, column-major) <- the input patch under each output pixel.
void conv2d_im2col(const Conv2dShape& shape, const float* input, float* patches);
// grad_input (in_size floats, the input's layout) <- the sum, over the patches each input
// float was copied into, of grad_patches (K x P): im2col's adjoint. Overwrites grad_input.
void conv2d_col2im(const Conv2dShape& shape, const float* grad_patches, float* grad_input);

// output (O x P) <- relu(weight * patches + bias) for one sample; `patches` is a K x P
// workspace that receives the sample's im2col.
void conv2d_forward_relu(const Conv2dShape& shape, const float* weight, const float* bias,
                         const float* input, float* patches, float* output);

// The backward pass of one sample's conv2d_forward_relu, given dL/d(output) in grad_output
// (O x P; overwritten with dL/d(pre-activation)) and that forward's output:
//   weight_grad (O x K) += dL/dW, bias_grad (O) += dL/db,
//   grad_input (in_size), when not null, <- dL/d(input), using weight_t = weight^T (K x O) and
//   grad_patches (a K x P workspace).
// `patches` must hold this sample's im2col (conv2d_im2col of the forward's input).
void conv2d_backward_relu(const Conv2dShape& shape, const float* weight_t, const float* patches,
                          const float* output, float* grad_output, float* weight_grad,
                          float* bias_grad, float* grad_patches, float* grad_input);

}  // namespace rlrun
