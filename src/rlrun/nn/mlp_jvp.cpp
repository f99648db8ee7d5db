// Mlp::jvp: the tangent of the network's output along a direction in parameter space, carried
// forward layer by layer through the activations the last forward() kept (the "R-operator" of
// Pearlmutter 1994, Neural Computation 6(1)): with z_l = W_l h_{l-1} + b_l and h_l = act(z_l),
//   dz_l = W_l dh_{l-1} + dW_l h_{l-1} + db_l,   dh_l = act'(z_l) * dz_l,   dh_0 = 0.
// It costs about one forward pass; torch gets the same numbers from double backward.
#include "rlrun/nn/mlp.hpp"

#include <utility>

namespace rlrun {

void Mlp::jvp(const Eigen::Ref<const Eigen::VectorXf>& d_params, Eigen::MatrixXf& d_output) const {
  const Eigen::Index batch = acts_.front().cols();
  Eigen::MatrixXf d_hidden, d_pre;  // dh_{l-1}, dz_l
  for (int l = 0; l < num_layers(); ++l) {
    const Eigen::Map<const Eigen::MatrixXf> d_weight(d_params.data() + w_offset_[l], layer_out(l),
                                                     layer_in(l));
    const Eigen::Map<const Eigen::VectorXf> d_bias(d_params.data() + b_offset_[l], layer_out(l));
    d_pre.noalias() = d_weight * acts_[l];
    if (l > 0) d_pre.noalias() += weight(l) * d_hidden;
    d_pre.colwise() += d_bias;
    if (l + 1 == num_layers()) break;
    // act'(z) * dz, with act' read off the stored activation as backward reads it.
    d_hidden.setZero(layer_out(l), batch);
    add_hidden_gradient(d_pre.data(), d_pre.rows(), derivative_source(l), layer_out(l), batch,
                        d_hidden);
  }
  d_output = std::move(d_pre);
}

}  // namespace rlrun
