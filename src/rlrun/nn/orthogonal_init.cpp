#include "rlrun/nn/orthogonal_init.hpp"

#include <Eigen/QR>
#include <algorithm>

namespace rlrun {

void orthogonal_init(Eigen::Ref<Eigen::MatrixXf> w, float gain, Rng& rng) {
  const Eigen::Index rows = w.rows();
  const Eigen::Index cols = w.cols();
  if (rows == 0 || cols == 0) return;
  // torch draws the (rows x cols) matrix and transposes it when rows < cols; we draw the tall
  // matrix directly. The draw order differs from torch anyway (different generator).
  const Eigen::Index tall = std::max(rows, cols);
  const Eigen::Index thin = std::min(rows, cols);
  Eigen::MatrixXd a(tall, thin);
  for (Eigen::Index j = 0; j < thin; ++j) {
    for (Eigen::Index i = 0; i < tall; ++i) a(i, j) = rng.normal();
  }
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(a);
  Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(tall, thin);
  // torch multiplies by d.sign(), which is 0 for an exactly zero diagonal entry (probability
  // zero with continuous draws); we use +1 there so Q never loses a column.
  const auto diag = qr.matrixQR().diagonal();
  for (Eigen::Index j = 0; j < thin; ++j) {
    if (diag(j) < 0.0) q.col(j) = -q.col(j);
  }
  if (rows < cols) {
    w = (gain * q.transpose()).cast<float>();
  } else {
    w = (gain * q).cast<float>();
  }
}

}  // namespace rlrun
