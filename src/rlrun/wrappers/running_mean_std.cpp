#include "rlrun/wrappers/running_mean_std.hpp"
#include "rlrun/core/state_dict.hpp"

namespace rlrun {

RunningMeanStd::RunningMeanStd(int dim)
    : mean_(Eigen::VectorXd::Zero(dim)), var_(Eigen::VectorXd::Ones(dim)) {}

void RunningMeanStd::update(std::span<const float> x) {
  // One sample: batch_mean = x, batch_var = 0, batch_count = 1, with SB3's operations in SB3's
  // order (bit-identical to numpy). Written out so that it does not allocate (once per step).
  const double tot_count = count_ + 1.0;
  for (int i = 0; i < dim(); ++i) {
    const double delta = static_cast<double>(x[i]) - mean_[i];
    const double m_a = var_[i] * count_;
    const double m_2 = m_a + delta * delta * count_ * 1.0 / tot_count;
    mean_[i] = mean_[i] + delta * 1.0 / tot_count;
    var_[i] = m_2 / tot_count;
  }
  count_ = tot_count;
}

void RunningMeanStd::update(double x) {
  const double tot_count = count_ + 1.0;
  const double delta = x - mean_[0];
  const double m_2 = var_[0] * count_ + delta * delta * count_ * 1.0 / tot_count;
  mean_[0] = mean_[0] + delta * 1.0 / tot_count;
  var_[0] = m_2 / tot_count;
  count_ = tot_count;
}

void RunningMeanStd::update_from_moments(const Eigen::VectorXd& batch_mean,
                                         const Eigen::VectorXd& batch_var, double batch_count) {
  const Eigen::VectorXd delta = batch_mean - mean_;
  const double tot_count = count_ + batch_count;
  const Eigen::VectorXd m_2 = var_ * count_ + batch_var * batch_count +
                              delta.array().square().matrix() * count_ * batch_count / tot_count;
  mean_ += delta * batch_count / tot_count;
  var_ = m_2 / tot_count;
  count_ = tot_count;
}

void RunningMeanStd::write(StateWriter& out) const {
  put_matrix(out, "mean", mean_);
  put_matrix(out, "var", var_);
  out.put_double("count", count_);
}

void RunningMeanStd::read(const StateReader& in) {
  get_matrix(in, "mean", mean_);
  get_matrix(in, "var", var_);
  count_ = in.get_double("count");
}

}  // namespace rlrun
