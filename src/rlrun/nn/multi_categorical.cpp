#include "rlrun/nn/multi_categorical.hpp"

#include <stdexcept>
#include <string>

namespace rlrun {

MultiCategorical::MultiCategorical(const std::vector<int64_t>& nvec) {
  if (nvec.empty()) throw std::invalid_argument("MultiCategorical: nvec is empty");
  for (int64_t n : nvec) {
    if (n < 1) throw std::invalid_argument("MultiCategorical: nvec entries must be >= 1");
    offsets_.push_back(num_logits_);
    num_logits_ += static_cast<int>(n);
  }
  parts_.resize(nvec.size());
}

void MultiCategorical::set_logits(const Eigen::Ref<const Eigen::MatrixXf>& logits) {
  if (logits.rows() != num_logits_)
    throw std::invalid_argument("MultiCategorical::set_logits: " + std::to_string(logits.rows()) +
                                " logits per column, expected " + std::to_string(num_logits_));
  const int entries = num_entries();
  for (int i = 0; i < entries; ++i) {
    const int end = i + 1 < entries ? offsets_[i + 1] : num_logits_;
    parts_[i].set_logits(logits.middleRows(offsets_[i], end - offsets_[i]));
  }
}

void MultiCategorical::set_logits(const Eigen::Ref<const Eigen::MatrixXf>& logits,
                                  const Eigen::Ref<const Eigen::MatrixXf>& masks) {
  if (logits.rows() != num_logits_ || masks.rows() != num_logits_)
    throw std::invalid_argument("MultiCategorical::set_logits: " + std::to_string(logits.rows()) +
                                " logits and " + std::to_string(masks.rows()) +
                                " mask entries per column, expected " +
                                std::to_string(num_logits_));
  const int entries = num_entries();
  for (int i = 0; i < entries; ++i) {
    const int end = i + 1 < entries ? offsets_[i + 1] : num_logits_;
    parts_[i].set_logits(logits.middleRows(offsets_[i], end - offsets_[i]),
                         masks.middleRows(offsets_[i], end - offsets_[i]));
  }
}

void MultiCategorical::load_row(const Eigen::Ref<const Eigen::MatrixXf>& actions, int i) {
  if (actions.rows() != num_entries() || actions.cols() != batch())
    throw std::invalid_argument("MultiCategorical: actions are " + std::to_string(actions.rows()) +
                                " x " + std::to_string(actions.cols()) + ", expected " +
                                std::to_string(num_entries()) + " x " + std::to_string(batch()));
  row_ = actions.row(i);
}

void MultiCategorical::log_prob(const Eigen::Ref<const Eigen::MatrixXf>& actions,
                                Eigen::Ref<Eigen::RowVectorXf> out) {
  part_out_.resize(batch());
  out.setZero();
  for (int i = 0; i < num_entries(); ++i) {
    load_row(actions, i);
    parts_[i].log_prob(row_, part_out_);
    out += part_out_;
  }
}

void MultiCategorical::entropy(Eigen::Ref<Eigen::RowVectorXf> out) {
  part_out_.resize(batch());
  out.setZero();
  for (const Categorical& part : parts_) {
    part.entropy(part_out_);
    out += part_out_;
  }
}

void MultiCategorical::sample(Rng& rng, Eigen::Ref<Eigen::MatrixXf> actions) {
  row_.resize(batch());
  for (int i = 0; i < num_entries(); ++i) {
    parts_[i].sample(rng, row_);
    actions.row(i) = row_;
  }
}

void MultiCategorical::mode(Eigen::Ref<Eigen::MatrixXf> actions) {
  row_.resize(batch());
  for (int i = 0; i < num_entries(); ++i) {
    parts_[i].mode(row_);
    actions.row(i) = row_;
  }
}

void MultiCategorical::backward(const Eigen::Ref<const Eigen::MatrixXf>& actions,
                                const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                                const Eigen::Ref<const Eigen::RowVectorXf>& grad_entropy,
                                Eigen::MatrixXf& grad_logits) {
  grad_logits.resize(num_logits_, batch());
  for (int i = 0; i < num_entries(); ++i) {
    load_row(actions, i);
    parts_[i].backward(row_, grad_log_prob, grad_entropy, part_grad_);
    grad_logits.middleRows(offsets_[i], part_grad_.rows()) = part_grad_;
  }
}

}  // namespace rlrun
