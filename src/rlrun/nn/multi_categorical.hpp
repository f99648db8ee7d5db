#pragma once
// One Categorical per entry of a MultiDiscrete(nvec) action: SB3 MultiCategoricalDistribution
// (stable_baselines3/common/distributions.py). The network outputs sum(nvec) logits per column;
// entry i's Categorical takes rows [offset_i, offset_i + nvec_i) (th.split), log_prob and
// entropy are the sums over the entries (th.stack(...).sum(dim=1)), the mode is the argmax of
// each entry. Actions are (entries x batch) integer-valued floats, as the rollout buffer keeps
// them.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "rlrun/nn/categorical.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {

class MultiCategorical {
 public:
  MultiCategorical() = default;
  // Throws std::invalid_argument for an empty nvec or an entry < 1.
  explicit MultiCategorical(const std::vector<int64_t>& nvec);

  int num_entries() const { return static_cast<int>(parts_.size()); }
  int num_logits() const { return num_logits_; }  // sum(nvec)
  Eigen::Index batch() const { return parts_.empty() ? 0 : parts_.front().batch(); }
  const Categorical& part(int i) const { return parts_[static_cast<size_t>(i)]; }

  // logits: sum(nvec) x batch. Buffers are reused for a repeated shape.
  void set_logits(const Eigen::Ref<const Eigen::MatrixXf>& logits);
  // With masks of the logits' shape (each entry's rows its own mask): sb3-contrib's
  // MaskableMultiCategoricalDistribution.apply_masking, Categorical::set_logits with masks.
  void set_logits(const Eigen::Ref<const Eigen::MatrixXf>& logits,
                  const Eigen::Ref<const Eigen::MatrixXf>& masks);

  // out(j) = sum_i log p_i(actions(i, j) | column j). Throws std::out_of_range for an entry
  // outside [0, nvec_i).
  void log_prob(const Eigen::Ref<const Eigen::MatrixXf>& actions,
                Eigen::Ref<Eigen::RowVectorXf> out);
  // out(j) = sum_i H_i(column j).
  void entropy(Eigen::Ref<Eigen::RowVectorXf> out);
  // One draw per entry and column (entry 0 for the whole batch first, then entry 1, ...).
  void sample(Rng& rng, Eigen::Ref<Eigen::MatrixXf> actions);
  // argmax of each entry, the first index on ties (SB3 mode()).
  void mode(Eigen::Ref<Eigen::MatrixXf> actions);

  // grad_logits = d/dlogits sum_j (grad_log_prob(j) log p(a_j) + grad_entropy(j) H_j); both
  // terms are sums over the entries, so each entry's block is that Categorical's gradient.
  // grad_logits is resized to sum(nvec) x batch if needed and overwritten.
  void backward(const Eigen::Ref<const Eigen::MatrixXf>& actions,
                const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                const Eigen::Ref<const Eigen::RowVectorXf>& grad_entropy,
                Eigen::MatrixXf& grad_logits);

 private:
  // Copies row i of `actions` into the contiguous row_ (a row of a column-major matrix has a
  // stride; Categorical takes contiguous rows).
  void load_row(const Eigen::Ref<const Eigen::MatrixXf>& actions, int i);

  std::vector<Categorical> parts_;
  std::vector<int> offsets_;  // first logit row of each entry
  int num_logits_ = 0;
  // Workspaces, reused while the batch size stays the same.
  Eigen::RowVectorXf row_, part_out_;
  Eigen::MatrixXf part_grad_;
};

}  // namespace rlrun
