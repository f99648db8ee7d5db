#include "rlrun/wrappers/running_mean_std.hpp"
#include "rlrun/core/state_dict.hpp"

#include <cmath>

namespace rlrun {

namespace {

// SB3 RunningMeanStd.update_from_moments for one coordinate, with SB3's operations in SB3's
// order (bit-identical to numpy); `m_b` is batch_var * batch_count, whose precision is the
// batch's (float32 for a batch of observations, 0 for a single sample).
void merge_moments(double& mean, double& var, double count, double batch_mean, double m_b,
                   double batch_count) {
  const double delta = batch_mean - mean;
  const double tot_count = count + batch_count;
  const double m_2 = var * count + m_b + delta * delta * count * batch_count / tot_count;
  mean = mean + delta * batch_count / tot_count;
  var = m_2 / tot_count;
}

}  // namespace

RunningMeanStd::RunningMeanStd(int dim)
    : mean_(Eigen::VectorXd::Zero(dim)), var_(Eigen::VectorXd::Ones(dim)) {}

void RunningMeanStd::update(std::span<const float> x) {
  // One sample: batch_mean = x, batch_var = 0, batch_count = 1. Per coordinate, so that it does
  // not allocate (once per step).
  for (int i = 0; i < dim(); ++i)
    merge_moments(mean_[i], var_[i], count_, static_cast<double>(x[i]), 0.0, 1.0);
  count_ += 1.0;
}

void RunningMeanStd::update(double x) {
  merge_moments(mean_[0], var_[0], count_, x, 0.0, 1.0);
  count_ += 1.0;
}

void RunningMeanStd::update_from_moments(const Eigen::VectorXd& batch_mean,
                                         const Eigen::VectorXd& batch_var, double batch_count) {
  for (int i = 0; i < dim(); ++i)
    merge_moments(mean_[i], var_[i], count_, batch_mean[i], batch_var[i] * batch_count,
                  batch_count);
  count_ += batch_count;
}

void RunningMeanStd::update_batch(const Eigen::Ref<const Eigen::MatrixXf>& samples,
                                  std::span<const int> rows, std::span<float> scratch) {
  const Eigen::Index n = samples.cols();
  const float n_float = static_cast<float>(n);
  std::span<float> sum = scratch.first(static_cast<size_t>(dim()));
  std::span<float> square_sum =
      scratch.subspan(static_cast<size_t>(dim()), static_cast<size_t>(dim()));
  auto row = [&](int k) { return rows.empty() ? k : rows[static_cast<size_t>(k)]; };
  // numpy reduces axis 0 of an (n, dim) float32 array sample by sample, in float32.
  for (int k = 0; k < dim(); ++k) {
    float s = samples(row(k), 0);
    for (Eigen::Index j = 1; j < n; ++j) s += samples(row(k), j);
    sum[static_cast<size_t>(k)] = s / n_float;  // np.mean: float32 sum / n
  }
  for (int k = 0; k < dim(); ++k) {
    const float mean = sum[static_cast<size_t>(k)];
    float d = samples(row(k), 0) - mean;
    float s = d * d;
    for (Eigen::Index j = 1; j < n; ++j) {
      d = samples(row(k), j) - mean;
      s += d * d;
    }
    square_sum[static_cast<size_t>(k)] = s / n_float;  // np.var (ddof 0)
  }
  // np.var of float32 is float32, and so is its product with the integer count.
  for (int k = 0; k < dim(); ++k)
    merge_moments(mean_[k], var_[k], count_, sum[static_cast<size_t>(k)],
                  square_sum[static_cast<size_t>(k)] * n_float, static_cast<double>(n));
  count_ += static_cast<double>(n);
}

void RunningMeanStd::update_batch(std::span<const double> values, std::span<double> scratch) {
  const double n = static_cast<double>(values.size());
  const double mean = pairwise_sum<double>(values) / n;  // np.mean
  for (size_t i = 0; i < values.size(); ++i) scratch[i] = (values[i] - mean) * (values[i] - mean);
  merge_moments(mean_[0], var_[0], count_, mean,
                pairwise_sum<double>(scratch.first(values.size())) / n * n, n);
  count_ += n;
}

void RunningMeanStd::write(StateWriter& out) const {
  put_matrix(out, "mean", mean_);
  put_matrix(out, "var", var_);
  out.put_double("count", count_);
}

void RunningMeanStd::read(const StateReader& in) {
  // From a model file or checkpoint (untrusted), or another env's statistics: they normalise
  // every observation or reward, so NaN, infinity or a negative variance is refused.
  Eigen::VectorXd mean(dim()), var(dim());
  get_matrix(in, "mean", mean);
  get_matrix(in, "var", var);
  const double count = in.get_double("count");
  const auto refuse = [&](const char* field, const char* why) {
    throw StateMismatch("statistics '" + in.prefix() + field + "' " + why);
  };
  if (!mean.allFinite()) refuse("mean", "is not finite");
  if (!var.allFinite() || (var.array() < 0).any()) refuse("var", "is not a finite variance >= 0");
  if (!std::isfinite(count) || count < 0) refuse("count", "is not a finite count >= 0");
  mean_ = mean;
  var_ = var;
  count_ = count;
}

}  // namespace rlrun
