#pragma once
// Invalid-action masking of categorical logits, as sb3-contrib 2.4's MaskableCategorical
// (sb3_contrib/common/maskable/distributions.py, apply_masking): the logit of every action
// whose mask entry is 0 is replaced by -1e8 before the softmax, so its probability is exactly
// 0 in float32 (exp(-1e8) underflows), it is never sampled nor the argmax, and it adds nothing
// to the entropy (sb3-contrib zeroes p log p there; Categorical::entropy gives 0 * finite = 0).
// Masks are 0/1 floats with the logits' shape: one row per logit (for MultiDiscrete the
// concatenation of each dimension's mask, MaskableMultiCategoricalDistribution's split).
#include <Eigen/Core>

namespace rlrun {

// sb3-contrib's HUGE_NEG.
inline constexpr float kMaskedLogit = -1e8f;

// out = where(masks != 0, logits, -1e8). Shapes must agree (std::invalid_argument otherwise).
void mask_logits(const Eigen::Ref<const Eigen::MatrixXf>& logits,
                 const Eigen::Ref<const Eigen::MatrixXf>& masks, Eigen::MatrixXf& out);

// The backward of mask_logits: th.where passes no gradient to the replaced logits, so the
// gradient entries of masked actions are set to 0 (in place).
void mask_logit_gradient(const Eigen::Ref<const Eigen::MatrixXf>& masks,
                         Eigen::MatrixXf& grad_logits);

}  // namespace rlrun
