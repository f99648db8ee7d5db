#pragma once
// torch.nn.init.orthogonal_ (Saxe et al. 2014, "Exact solutions to the nonlinear dynamics of
// learning in deep linear neural networks"), which SB3 applies to every Linear layer
// (common/policies.py BasePolicy.init_weights) with gains sqrt(2) for the feature layers, 0.01
// for the policy head and 1 for the value head.
#include <Eigen/Core>

#include "rlrun/rng.hpp"

namespace rlrun {

// Fills w (rows x cols) with a random (semi-)orthogonal matrix times gain: the rows are
// orthonormal when rows <= cols, the columns when rows >= cols. Same recipe as torch: a standard
// normal matrix, made tall by transposing when rows < cols, thin QR, columns of Q multiplied by
// sign(diag(R)) so that the result is Haar-distributed and independent of the QR algorithm,
// transposed back, scaled. The QR runs in double precision.
void orthogonal_init(Eigen::Ref<Eigen::MatrixXf> w, float gain, Rng& rng);

}  // namespace rlrun
