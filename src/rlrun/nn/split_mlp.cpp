#include "rlrun/nn/split_mlp.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "rlrun/nn/batch_split.hpp"

namespace rlrun {

SplitMlp::SplitMlp(int in_dim, std::vector<int> hidden, int out_dim, Activation act,
                   ThreadPool* pool)
    : net_(in_dim, std::move(hidden), out_dim, act), pool_(pool) {}

SplitMlp::SplitMlp(Mlp net, ThreadPool* pool) : net_(std::move(net)), pool_(pool) {}

SplitMlp& SplitMlp::operator=(const SplitMlp& other) {
  if (this == &other) return *this;
  net_ = other.net_;
  pool_ = other.pool_;
  replicas_.clear();
  parts_ = 1;
  return *this;
}

Mlp& SplitMlp::part_net(int k) {
  if (k == 0) return net_;
  while (static_cast<int>(replicas_.size()) < k) {
    replicas_.emplace_back(net_.in_dim(), net_.hidden(), net_.out_dim(), net_.activation());
    replicas_.back().params_.resize(0);  // it reads net_'s
  }
  return replicas_[static_cast<size_t>(k - 1)];
}

const Eigen::MatrixXf& SplitMlp::forward(const Eigen::Ref<const Eigen::MatrixXf>& x) {
  const Eigen::Index n = x.cols();
  parts_ = column_parts(n, net_.multiply_adds_per_column());
  if (parts_ == 1) return net_.forward(x);
  part_net(parts_ - 1);  // every replica exists before the parts run
  const float* p = net_.params_.data();
  output_.resize(net_.out_dim(), n);
  run_parts(pool_, parts_, [&](int k) {
    const Part cols = column_part(n, parts_, k);
    output_.middleCols(cols.begin, cols.count) =
        part_net(k).forward_with(p, x.middleCols(cols.begin, cols.count));
  });
  return output_;
}

void SplitMlp::backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_output) {
  backward_parts(grad_output, false);
}

void SplitMlp::zero_grad_and_backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_output,
                                      const Eigen::MatrixXf* grad_last_hidden,
                                      Eigen::MatrixXf* grad_input) {
  backward_parts(grad_output, true, grad_last_hidden, grad_input);
}

const Eigen::MatrixXf& SplitMlp::last_hidden() {
  if (parts_ == 1) return net_.last_hidden();
  const Eigen::Index n = output_.cols();
  last_hidden_.resize(net_.last_hidden().rows(), n);
  for (int k = 0; k < parts_; ++k) {
    const Part cols = column_part(n, parts_, k);
    last_hidden_.middleCols(cols.begin, cols.count) = part_net(k).last_hidden();
  }
  return last_hidden_;
}

void SplitMlp::backward_parts(const Eigen::Ref<const Eigen::MatrixXf>& grad_output, bool zero_first,
                              const Eigen::MatrixXf* grad_last_hidden,
                              Eigen::MatrixXf* grad_input) {
  if (parts_ == 1) {
    if (zero_first) net_.zero_grad();
    net_.backward(grad_output, grad_input, grad_last_hidden);
    return;
  }
  if (grad_last_hidden != nullptr && grad_last_hidden->cols() != grad_output.cols())
    throw std::invalid_argument("SplitMlp::backward: grad_last_hidden has the wrong batch");
  const Eigen::Index n = grad_output.cols();
  const float* p = net_.params_.data();
  if (grad_input) grad_input->resize(net_.in_dim(), n);
  transpose_for_parts(n, grad_input != nullptr);
  run_parts(pool_, parts_, [&](int k) {
    const Part cols = column_part(n, parts_, k);
    Mlp& part = part_net(k);
    if (k > 0 || zero_first) part.zero_grad();  // a replica holds its part's gradient alone
    const float* grad_hidden =
        grad_last_hidden ? grad_last_hidden->data() + cols.begin * grad_last_hidden->rows()
                         : nullptr;
    float* grad_x = grad_input ? grad_input->data() + cols.begin * grad_input->rows() : nullptr;
    part.backward_pass(p, grad_output.middleCols(cols.begin, cols.count), true, grad_x, 0,
                       grad_hidden, grad_last_hidden ? grad_last_hidden->rows() : 0, &net_);
  });
  // grads += part 1's, then part 2's, ...: the same order for every element, each of two
  // threads adding into its own cache lines of the parameter vector.
  run_parts(pool_, 2, [&](int k) {
    const Part params = param_part(net_.num_params(), k);
    auto grads = net_.grads_.segment(params.begin, params.count);
    for (int r = 1; r < parts_; ++r)
      grads += part_net(r).grads_.segment(params.begin, params.count);
  });
}

void SplitMlp::backward_input(const Eigen::Ref<const Eigen::MatrixXf>& grad_output,
                              Eigen::MatrixXf& grad_input, int first_input_row) {
  if (parts_ == 1) {
    net_.backward_input(grad_output, grad_input, first_input_row);
    return;
  }
  if (first_input_row < 0 || first_input_row >= net_.in_dim())
    throw std::invalid_argument("SplitMlp::backward_input: first_input_row " +
                                std::to_string(first_input_row) + " is not below in_dim " +
                                std::to_string(net_.in_dim()));
  const Eigen::Index n = grad_output.cols();
  const float* p = net_.params_.data();
  grad_input.resize(net_.in_dim() - first_input_row, n);
  transpose_for_parts(n, true, first_input_row);
  run_parts(pool_, parts_, [&](int k) {
    const Part cols = column_part(n, parts_, k);
    part_net(k).backward_pass(p, grad_output.middleCols(cols.begin, cols.count), false,
                              grad_input.data() + cols.begin * grad_input.rows(), first_input_row,
                              nullptr, 0, &net_);
  });
}

void SplitMlp::transpose_for_parts(Eigen::Index n, bool input_gradient, int first_input_row) {
  // A layer is transposed when any part's backward_pass would use W^T (the largest part's
  // batch decides); each part still chooses its kernel from its own batch.
  Eigen::Index batch = 0;
  for (int k = 0; k < parts_; ++k) batch = std::max(batch, column_part(n, parts_, k).count);
  const float* p = net_.params_.data();
  run_parts(pool_, 2, [&](int k) {
    for (int l = input_gradient ? 0 : 1; l < net_.num_layers(); ++l) {
      const Eigen::Index in = net_.dims_[l];
      if (!Mlp::uses_transposed_weight(l == 0 ? in - first_input_row : in, batch)) continue;
      const Part rows = param_part(in, k);  // whole cache lines of each W^T column per thread
      net_.transpose_weight_rows(p, l, rows.begin, rows.count);
    }
  });
}

}  // namespace rlrun
