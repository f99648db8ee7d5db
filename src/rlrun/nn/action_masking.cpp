#include "rlrun/nn/action_masking.hpp"

#include <stdexcept>
#include <string>

namespace rlrun {

namespace {
void check_shape(const Eigen::Ref<const Eigen::MatrixXf>& masks, Eigen::Index rows,
                 Eigen::Index cols) {
  if (masks.rows() != rows || masks.cols() != cols)
    throw std::invalid_argument("action masks are " + std::to_string(masks.rows()) + " x " +
                                std::to_string(masks.cols()) + ", the logits " +
                                std::to_string(rows) + " x " + std::to_string(cols));
}
}  // namespace

void mask_logits(const Eigen::Ref<const Eigen::MatrixXf>& logits,
                 const Eigen::Ref<const Eigen::MatrixXf>& masks, Eigen::MatrixXf& out) {
  check_shape(masks, logits.rows(), logits.cols());
  out = (masks.array() != 0.0f).select(logits, kMaskedLogit);
}

void mask_logit_gradient(const Eigen::Ref<const Eigen::MatrixXf>& masks,
                         Eigen::MatrixXf& grad_logits) {
  check_shape(masks, grad_logits.rows(), grad_logits.cols());
  grad_logits = (masks.array() != 0.0f).select(grad_logits, 0.0f);
}

}  // namespace rlrun
