#include "rlrun/runtime/io/non_finite_check.hpp"

#include <cmath>
#include <cstring>
#include <vector>

namespace rlrun {

namespace {

std::string name_value(double v) { return std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf"); }

template <class T>
std::string check_values(const std::string& noun, const std::string& name, const Tensor& t) {
  std::vector<T> values(t.bytes.size() / sizeof(T));
  if (!values.empty()) std::memcpy(values.data(), t.bytes.data(), values.size() * sizeof(T));
  int64_t bad = 0;
  double first = 0.0;
  for (const T v : values) {
    if (std::isfinite(v)) continue;
    if (bad++ == 0) first = static_cast<double>(v);
  }
  if (bad == 0) return "";
  return noun + " " + name + " has " + std::to_string(bad) + " non-finite value" +
         (bad == 1 ? "" : "s") + " (first: " + name_value(first) + ")";
}

}  // namespace

std::string describe_non_finite(const LogRow& row) {
  // Losses only: other diagnostics are legitimately nan at times (SB3's explained_variance is
  // nan when the returns have zero variance).
  for (const auto& [key, value] : row)
    if (key.rfind("train/", 0) == 0 && key.find("loss") != std::string::npos &&
        !std::isfinite(value))
      return key + " is " + name_value(value);
  return "";
}

std::string describe_non_finite(const TensorMap& tensors, const std::string& noun) {
  for (const auto& [name, tensor] : tensors) {
    std::string problem;
    if (tensor.dtype == DType::kFloat32) problem = check_values<float>(noun, name, tensor);
    if (tensor.dtype == DType::kFloat64) problem = check_values<double>(noun, name, tensor);
    if (!problem.empty()) return problem;
  }
  return "";
}

}  // namespace rlrun
