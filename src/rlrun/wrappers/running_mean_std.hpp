#pragma once
// Running mean and variance of a stream of vectors: SB3's RunningMeanStd
// (stable_baselines3/common/running_mean_std.py), the parallel-update algorithm of Chan et al.
// (Wikipedia "Algorithms for calculating variance", parallel algorithm). Starts, as SB3 does,
// at mean 0, var 1 and count 1e-4 (the "epsilon" that keeps the first update finite).
// Everything is float64 like SB3's numpy arrays.
#include <Eigen/Core>
#include <span>

#include "rlrun/core/pairwise_sum.hpp"

#include "rlrun/core/state_dict.hpp"

namespace rlrun {

class RunningMeanStd {
 public:
  static constexpr double kInitialCount = 1e-4;

  explicit RunningMeanStd(int dim = 1);

  // update_from_moments with a batch of one sample (batch mean = x, batch var = 0).
  void update(std::span<const float> x);
  void update(double x);  // dim 1
  // SB3 update_from_moments: merges a batch of `batch_count` samples with the given moments.
  void update_from_moments(const Eigen::VectorXd& batch_mean, const Eigen::VectorXd& batch_var,
                           double batch_count);
  // SB3 update(arr) for a batch of float32 samples, one per column of `samples` (only the rows
  // listed in `rows`, when not empty): numpy's float32 np.mean / np.var over axis 0 (summed
  // sample by sample, divided in float32), then update_from_moments. `scratch` holds 2 * dim()
  // floats; nothing is allocated.
  void update_batch(const Eigen::Ref<const Eigen::MatrixXf>& samples, std::span<const int> rows,
                    std::span<float> scratch);
  // The same for a batch of float64 values (dim 1), SB3's ret_rms.update(returns): numpy's
  // pairwise sums. `scratch` holds values.size() doubles.
  void update_batch(std::span<const double> values, std::span<double> scratch);

  int dim() const { return static_cast<int>(mean_.size()); }
  const Eigen::VectorXd& mean() const { return mean_; }
  const Eigen::VectorXd& var() const { return var_; }
  double count() const { return count_; }

  // Stored as `mean`, `var` (float64, shape (dim,)) and `count` (float64 scalar), the fields of
  // SB3's object. read() throws StateMismatch when the stored dimension differs, a value is
  // not finite, or a variance or the count is negative (leaving the statistics as they were).
  void write(StateWriter& out) const;
  void read(const StateReader& in);

 private:
  Eigen::VectorXd mean_, var_;
  double count_ = kInitialCount;
};

}  // namespace rlrun
