#include "rlrun/nn/batch_renorm_mlp.hpp"

#include <stdexcept>
#include <utility>

#include "rlrun/nn/elementwise_activation.hpp"

namespace rlrun {

BatchRenormMlp::BatchRenormMlp(int in_dim, std::vector<int> hidden, int out_dim, Activation act,
                               bool batch_norm, const BatchRenormOptions& bn, ThreadPool* pool)
    : in_dim_(in_dim), hidden_(std::move(hidden)), act_(act) {
  if (in_dim < 1 || out_dim < 0) throw std::invalid_argument("BatchRenormMlp: bad sizes");
  // create_mlp: pre_linear_modules (the BatchRenorm) before every Linear.
  const auto add_stage = [&](int from, int to, bool activated) {
    Stage s;
    if (batch_norm) s.norm.emplace(from, bn);
    s.linear = SplitMlp(from, {}, to, act, pool);
    s.activated = activated;
    stages_.push_back(std::move(s));
  };
  int width = in_dim;
  for (int h : hidden_) {
    if (h < 1) throw std::invalid_argument("BatchRenormMlp: layer sizes must be positive");
    add_stage(width, h, true);
    width = h;
  }
  if (out_dim > 0) {
    add_stage(width, out_dim, false);
    width = out_dim;
  } else if (batch_norm && !hidden_.empty()) {
    trailing_.emplace(width, bn);  // CrossQ Actor: `latent_pi_net.append(BatchRenorm1d(...))`
  }
  out_dim_ = width;
}

Eigen::Index BatchRenormMlp::multiply_adds_per_column() const {
  Eigen::Index total = 0;
  for (const Stage& s : stages_) total += s.linear.net().multiply_adds_per_column();
  return total;
}

void BatchRenormMlp::init_torch_default(Rng& rng) {
  for (Stage& s : stages_) s.linear.net().init_torch_default(rng);
}

std::vector<ParamBlock> BatchRenormMlp::blocks() {
  std::vector<ParamBlock> out;
  for (Stage& s : stages_) {
    if (s.norm) out.push_back(s.norm->block());
    out.push_back(s.linear.net().block());
  }
  if (trailing_) out.push_back(trailing_->block());
  return out;
}

void BatchRenormMlp::zero_grad() {
  for (Stage& s : stages_) {
    if (s.norm) s.norm->zero_grad();
    s.linear.zero_grad();
  }
  if (trailing_) trailing_->zero_grad();
}

void BatchRenormMlp::copy_state_from(const BatchRenormMlp& other) {
  for (size_t l = 0; l < stages_.size(); ++l) {
    if (stages_[l].norm) stages_[l].norm->copy_state_from(*other.stages_[l].norm);
    stages_[l].linear.params() = other.stages_[l].linear.params();
  }
  if (trailing_) trailing_->copy_state_from(*other.trailing_);
}

const Eigen::MatrixXf& BatchRenormMlp::forward(const Eigen::Ref<const Eigen::MatrixXf>& x,
                                               bool training) {
  if (stages_.empty()) {
    input_copy_ = x;  // create_mlp(in, -1, []): no module at all
    return input_copy_;
  }
  const auto run = [&](Stage & s, const Eigen::Ref<const Eigen::MatrixXf>& in) -> auto& {
    const Eigen::MatrixXf& z =
        s.norm ? s.linear.forward(s.norm->forward(in, training)) : s.linear.forward(in);
    if (!s.activated) return z;
    apply_activation(act_, z, s.act);
    return std::as_const(s.act);
  };
  const Eigen::MatrixXf* h = &run(stages_.front(), x);
  for (size_t l = 1; l < stages_.size(); ++l) h = &run(stages_[l], *h);
  return trailing_ ? trailing_->forward(*h, training) : *h;
}

const Eigen::MatrixXf& BatchRenormMlp::output() const {
  if (stages_.empty()) return input_copy_;
  if (trailing_) return trailing_->output();
  const Stage& s = stages_.back();
  return s.activated ? s.act : s.linear.output();
}

void BatchRenormMlp::backward_stage(int l, bool param_grads, bool input_gradient) {
  Stage& s = stages_[l];
  if (s.activated) {
    activation_backward(act_, s.linear.output(), s.act, grad_, grad_linear_in_);
    grad_.swap(grad_linear_in_);  // grad_ = dL/dz
  }
  const bool linear_input = input_gradient || (s.norm && param_grads);
  if (param_grads)
    s.linear.zero_grad_and_backward(grad_, nullptr, linear_input ? &grad_linear_in_ : nullptr);
  else
    s.linear.backward_input(grad_, grad_linear_in_);
  if (!linear_input) return;
  if (s.norm) {
    if (param_grads) s.norm->zero_grad();
    s.norm->backward(grad_linear_in_, grad_, param_grads);
  } else {
    grad_.swap(grad_linear_in_);
  }
}

void BatchRenormMlp::zero_grad_and_backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_output,
                                            Eigen::MatrixXf* grad_input) {
  if (stages_.empty()) {
    if (grad_input) *grad_input = grad_output;
    return;
  }
  if (trailing_) {
    trailing_->zero_grad();
    trailing_->backward(grad_output, grad_);
  } else {
    grad_ = grad_output;
  }
  for (int l = num_linear() - 1; l >= 0; --l) backward_stage(l, true, l > 0 || grad_input);
  if (grad_input) *grad_input = grad_;
}

void BatchRenormMlp::backward_input(const Eigen::Ref<const Eigen::MatrixXf>& grad_output,
                                    Eigen::MatrixXf& grad_input, int first_input_row) {
  const int rows = in_dim_ - first_input_row;
  if (stages_.empty()) {
    grad_input = grad_output.bottomRows(rows);
    return;
  }
  if (trailing_) {
    trailing_->backward(grad_output, grad_, false);
  } else {
    grad_ = grad_output;
  }
  for (int l = num_linear() - 1; l >= 1; --l) backward_stage(l, false, true);
  Stage& s = stages_.front();
  if (s.activated) {
    activation_backward(act_, s.linear.output(), s.act, grad_, grad_linear_in_);
    grad_.swap(grad_linear_in_);
  }
  s.linear.backward_input(grad_, grad_input, first_input_row);
  if (!s.norm) return;
  // Eval mode: the BatchRenorm is scale / sqrt(ra_var + eps) per feature (in train mode the
  // rows would mix through the batch statistics).
  if (s.norm->last_training())
    throw std::logic_error("BatchRenormMlp::backward_input needs an eval-mode forward");
  const Eigen::VectorXf factor =
      (s.norm->scale().array() * s.norm->last_inv_std().array()).tail(rows);
  grad_input = (grad_input.array().colwise() * factor.array()).matrix();
}

Mlp BatchRenormMlp::folded(const Mlp* head) const {
  const bool has_output = stages_.size() > hidden_.size();
  if (head ? has_output : !has_output)
    throw std::logic_error(
        "BatchRenormMlp::folded: a head goes on a network without an output layer, and only "
        "there");
  const int out = head ? head->out_dim() : out_dim_;
  Mlp m(in_dim_, hidden_, out, act_);
  // Linear(a * x + c) = (W diag(a)) x + (b + W c).
  const auto fold = [&m](int layer, const Mlp& linear, const BatchRenorm* norm) {
    m.weight(layer) = linear.weight(0);
    m.bias(layer) = linear.bias(0);
    if (!norm) return;
    const Eigen::VectorXf a = norm->eval_scale(), c = norm->eval_shift();
    m.bias(layer) += linear.weight(0) * c;
    m.weight(layer) = linear.weight(0) * a.asDiagonal();
  };
  for (int l = 0; l < num_linear(); ++l) fold(l, linear(l), norm(l));
  if (head) fold(num_linear(), *head, trailing_norm());
  return m;
}

void BatchRenormMlp::module_indices(int l, int& norm_index, int& linear_index) const {
  int k = 0;
  for (int i = 0; i < l; ++i) k += (stages_[i].norm ? 1 : 0) + 1 + (stages_[i].activated ? 1 : 0);
  norm_index = stages_[l].norm ? k : -1;
  linear_index = stages_[l].norm ? k + 1 : k;
}

int BatchRenormMlp::trailing_index() const {
  int norm_index = 0, linear_index = 0;
  module_indices(num_linear() - 1, norm_index, linear_index);
  return linear_index + 2;  // after the last Linear and its activation
}

void BatchRenormMlp::save(const std::string& prefix, TensorMap& tensors) const {
  for (int l = 0; l < num_linear(); ++l) {
    int norm_index = 0, linear_index = 0;
    module_indices(l, norm_index, linear_index);
    if (const BatchRenorm* n = norm(l)) n->save(prefix + "." + std::to_string(norm_index), tensors);
    const std::string name = prefix + "." + std::to_string(linear_index);
    tensors[name + ".weight"] = to_tensor(Eigen::MatrixXf(linear(l).weight(0)));
    tensors[name + ".bias"] = to_tensor(Eigen::VectorXf(linear(l).bias(0)));
  }
  if (trailing_) trailing_->save(prefix + "." + std::to_string(trailing_index()), tensors);
}

void BatchRenormMlp::load(const std::string& prefix, const TensorMap& tensors) {
  for (int l = 0; l < num_linear(); ++l) {
    int norm_index = 0, linear_index = 0;
    module_indices(l, norm_index, linear_index);
    if (stages_[l].norm) stages_[l].norm->load(prefix + "." + std::to_string(norm_index), tensors);
    const std::string name = prefix + "." + std::to_string(linear_index);
    from_tensor(tensors, name + ".weight", linear(l).weight(0));
    from_tensor(tensors, name + ".bias", linear(l).bias(0));
  }
  if (trailing_) trailing_->load(prefix + "." + std::to_string(trailing_index()), tensors);
}

}  // namespace rlrun
