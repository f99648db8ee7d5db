#pragma once
// Eigen matrices in and out of tensors (rlrun/tensor.hpp). Eigen matrices are column-major;
// to_tensor/from_tensor transpose so that a (out x in) weight reads in numpy exactly like
// torch's `weight` of shape (out, in).
#include <Eigen/Core>
#include <cstdint>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "rlrun/tensor.hpp"

namespace rlrun {

// Matrix (rows x cols) -> tensor of shape (rows, cols) in C order; a vector -> shape (n,).
template <class Scalar, int R, int C, int O, int MR, int MC>
Tensor to_tensor(const Eigen::Matrix<Scalar, R, C, O, MR, MC>& m, bool as_vector = false) {
  Tensor t;
  t.dtype = dtype_of<Scalar>();
  if (as_vector || C == 1)
    t.shape = {static_cast<int64_t>(m.size())};
  else
    t.shape = {static_cast<int64_t>(m.rows()), static_cast<int64_t>(m.cols())};
  t.bytes.resize(m.size() * sizeof(Scalar));
  Eigen::Map<Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> out(
      t.data<Scalar>(), m.rows(), m.cols());
  out = m;
  return t;
}

template <class T>
Tensor scalar_tensor(T value) {
  Tensor t;
  t.dtype = dtype_of<T>();
  t.shape = {};
  t.bytes.resize(sizeof(T));
  std::memcpy(t.bytes.data(), &value, sizeof(T));
  return t;
}

template <class T>
Tensor vector_tensor(const std::vector<T>& values) {
  Tensor t;
  t.dtype = dtype_of<T>();
  t.shape = {static_cast<int64_t>(values.size())};
  t.bytes.resize(values.size() * sizeof(T));
  if (!values.empty()) std::memcpy(t.bytes.data(), values.data(), t.bytes.size());
  return t;
}

// Copies a stored tensor into `m`, which must already have the stored shape (the model
// config decides shapes; a mismatch means the file does not belong to this model).
template <class Derived>
void from_tensor(const TensorMap& tensors, const std::string& name,
                 Eigen::MatrixBase<Derived>&& m) {
  using Scalar = typename Derived::Scalar;
  const auto it = tensors.find(name);
  if (it == tensors.end()) throw std::runtime_error("model file has no tensor '" + name + "'");
  const Tensor& t = it->second;
  if (t.dtype != dtype_of<Scalar>() || t.numel() != m.size() ||
      (t.shape.size() == 2 && (t.shape[0] != m.rows() || t.shape[1] != m.cols())))
    throw std::runtime_error("tensor '" + name + "' has a different shape or type than the model");
  m = Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      t.data<Scalar>(), m.rows(), m.cols());
}
template <class Derived>
void from_tensor(const TensorMap& tensors, const std::string& name, Eigen::MatrixBase<Derived>& m) {
  from_tensor(tensors, name, std::move(m));
}

template <class T>
T scalar_from(const TensorMap& tensors, const std::string& name) {
  const auto it = tensors.find(name);
  if (it == tensors.end()) throw std::runtime_error("model file has no tensor '" + name + "'");
  if (it->second.dtype != dtype_of<T>() || it->second.numel() != 1)
    throw std::runtime_error("tensor '" + name + "' is not a scalar of the expected type");
  T v;
  std::memcpy(&v, it->second.bytes.data(), sizeof(T));
  return v;
}

}  // namespace rlrun
