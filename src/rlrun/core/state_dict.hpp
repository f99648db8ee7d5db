#pragma once
// Eigen matrices in and out of a saved state (rlrun/state.hpp): rlrun's algorithms, buffers
// and envs store their matrices with their shapes.
#include <Eigen/Core>
#include <string>

#include "rlrun/core/tensor.hpp"
#include "rlrun/state.hpp"

namespace rlrun {

// Any Eigen matrix or vector (stored with its shape; a vector as shape (n,)).
template <class Derived>
void put_matrix(StateWriter& out, const std::string& name, const Eigen::MatrixBase<Derived>& m) {
  using Scalar = typename Derived::Scalar;
  const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> dense = m;
  out.tensors()[out.prefix() + name] = to_tensor(dense, Derived::ColsAtCompileTime == 1);
}
template <class Derived>
void put_matrix(StateWriter&& out, const std::string& name, const Eigen::MatrixBase<Derived>& m) {
  put_matrix(out, name, m);
}

// Reads into `m`, which must already have the stored shape (fixed by the configuration).
template <class Derived>
void get_matrix(const StateReader& in, const std::string& name, Eigen::MatrixBase<Derived>& m) {
  using Scalar = typename Derived::Scalar;
  in.find(name, dtype_of<Scalar>());
  try {
    from_tensor(in.tensors(), in.prefix() + name, m);
  } catch (const std::exception& e) {
    throw StateMismatch("checkpoint state '" + in.prefix() + name + "': " + e.what());
  }
}
template <class Derived>
void get_matrix(const StateReader& in, const std::string& name, Eigen::MatrixBase<Derived>&& m) {
  get_matrix(in, name, m);
}

// get_matrix for numbers that must be finite (optimizer moments, network parameters): a NaN
// there makes the first update NaN, so a resumed run would diverge at once. Throws
// StateMismatch naming the key.
template <class Derived>
void get_finite_matrix(const StateReader& in, const std::string& name,
                       Eigen::MatrixBase<Derived>& m) {
  get_matrix(in, name, m);
  if (!m.allFinite())
    throw StateMismatch("checkpoint state '" + in.prefix() + name +
                        "' holds a NaN or infinite value (the checkpoint is damaged)");
}
template <class Derived>
void get_finite_matrix(const StateReader& in, const std::string& name,
                       Eigen::MatrixBase<Derived>&& m) {
  get_finite_matrix(in, name, m);
}

}  // namespace rlrun
