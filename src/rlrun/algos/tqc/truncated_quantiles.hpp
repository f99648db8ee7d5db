#pragma once
// TQC's control of overestimation (Kuznetsov et al. 2020, arXiv:2005.04269, section 3;
// sb3-contrib tqc/tqc.py train): the target critics' quantiles at (s', a') of all networks
// pooled into one mixture, sorted ascending (th.sort over the flattened n_critics x n_quantiles
// atoms) and only the lowest n_target = n_critics * (n_quantiles - top_quantiles_to_drop_per_net)
// kept. The soft Bellman backup of the kept atoms is TQC::train_on_batch's.
#include <Eigen/Core>
#include <vector>

namespace rlrun {

// next_quantiles: one matrix per target critic (n_quantiles x n; column j is sample j). Writes
// the n_target smallest of each sample's pooled atoms in ascending order to `out` (n_target x n,
// resized). `pooled` is a reused workspace. Throws std::invalid_argument when n_target is not in
// [1, pooled atoms] or the matrices' sizes differ.
void truncated_quantiles(const std::vector<const Eigen::MatrixXf*>& next_quantiles, int n_target,
                         Eigen::MatrixXf& out, std::vector<float>& pooled);

}  // namespace rlrun
