#include "rlrun/algos/tqc/truncated_quantiles.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace rlrun {

void truncated_quantiles(const std::vector<const Eigen::MatrixXf*>& next_quantiles, int n_target,
                         Eigen::MatrixXf& out, std::vector<float>& pooled) {
  if (next_quantiles.empty()) throw std::invalid_argument("truncated_quantiles: no critics");
  const Eigen::Index n_quantiles = next_quantiles.front()->rows();
  const Eigen::Index n = next_quantiles.front()->cols();
  for (const Eigen::MatrixXf* q : next_quantiles)
    if (q->rows() != n_quantiles || q->cols() != n)
      throw std::invalid_argument("truncated_quantiles: the critics' outputs differ in size");
  const auto total = static_cast<Eigen::Index>(next_quantiles.size()) * n_quantiles;
  if (n_target < 1 || n_target > total)
    throw std::invalid_argument("truncated_quantiles: n_target must be in [1, " +
                                std::to_string(total) + "], got " + std::to_string(n_target));
  pooled.resize(static_cast<size_t>(total));
  out.resize(n_target, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    // next_quantiles.reshape(batch_size, -1): critic 0's atoms, then critic 1's, ...
    auto it = pooled.begin();
    for (const Eigen::MatrixXf* q : next_quantiles)
      it = std::copy(q->col(j).data(), q->col(j).data() + n_quantiles, it);
    // th.sort(...)[:, :n_target]: only the smallest n_target need their order.
    std::partial_sort(pooled.begin(), pooled.begin() + n_target, pooled.end());
    std::copy(pooled.begin(), pooled.begin() + n_target, out.col(j).data());
  }
}

}  // namespace rlrun
