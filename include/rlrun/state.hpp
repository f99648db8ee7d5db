#pragma once
// Saved state for exact resume (checkpoints): named tensors in a TensorMap, under
// slash-separated prefixes ("algo/actor/adam_m", "env/3/time_limit/elapsed"). A checkpoint is
// a model file whose tensors also hold this state, so `numpy.load` still opens it. Part of the
// plugin API: an env that can save its state (Env::write_state) writes it through these.
// rlrun's Eigen helpers (put_matrix / get_matrix) are in src/rlrun/core/state_dict.hpp.
//
// StateWriter puts, StateReader gets: every get names the full key when it is missing or has
// another dtype or shape, so a checkpoint from another configuration is refused with a reason
// instead of resuming into a silently different run.
#include <algorithm>
#include <bit>
#include <climits>
#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "rlrun/rng.hpp"
#include "rlrun/tensor.hpp"

namespace rlrun {

// Thrown by StateReader when the stored state does not fit (missing key, dtype, shape).
class StateMismatch : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class StateWriter {
 public:
  StateWriter(TensorMap& tensors, std::string prefix = "")
      : tensors_(tensors), prefix_(std::move(prefix)) {}

  // A writer whose keys start with "<prefix><name>/".
  StateWriter sub(const std::string& name) const {
    return StateWriter(tensors_, prefix_ + name + "/");
  }
  const std::string& prefix() const { return prefix_; }
  TensorMap& tensors() const { return tensors_; }

  void put_int(const std::string& name, int64_t value) { put_span<int64_t>(name, {&value, 1}); }
  void put_double(const std::string& name, double value) { put_span<double>(name, {&value, 1}); }
  void put_bool(const std::string& name, bool value) { put_int(name, value ? 1 : 0); }

  template <class T>
  void put_span(const std::string& name, std::span<const T> values) {
    Tensor t;
    t.dtype = dtype_of<T>();
    t.shape = {static_cast<int64_t>(values.size())};
    t.bytes.resize(values.size() * sizeof(T));
    if (!values.empty()) std::memcpy(t.bytes.data(), values.data(), t.bytes.size());
    tensors_[prefix_ + name] = std::move(t);
  }
  template <class T>
  void put_vector(const std::string& name, const std::vector<T>& values) {
    put_span<T>(name, std::span<const T>(values.data(), values.size()));
  }

  // Text (a CSV header, a file name), one int64 per byte: numpy shows it as a number array.
  void put_string(const std::string& name, const std::string& text) {
    std::vector<int64_t> bytes(text.begin(), text.end());
    put_vector(name, bytes);
  }

  void put_rng(const std::string& name, const Rng& rng) {
    const Rng::State& s = rng.state();
    const uint64_t words[6] = {s.s[0],
                               s.s[1],
                               s.s[2],
                               s.s[3],
                               s.has_spare_normal ? 1u : 0u,
                               std::bit_cast<uint64_t>(s.spare_normal)};
    put_span<uint64_t>(name, words);
  }

 private:
  TensorMap& tensors_;
  std::string prefix_;
};

class StateReader {
 public:
  StateReader(const TensorMap& tensors, std::string prefix = "")
      : tensors_(tensors), prefix_(std::move(prefix)) {}

  StateReader sub(const std::string& name) const {
    return StateReader(tensors_, prefix_ + name + "/");
  }
  const std::string& prefix() const { return prefix_; }
  bool has(const std::string& name) const { return tensors_.count(prefix_ + name) != 0; }

  int64_t get_int(const std::string& name) const { return get_span<int64_t>(name, 1)[0]; }
  // A counter or index that must lie in [low, high]: a checkpoint is untrusted data, and a
  // value used as an index is checked before it is used (StateMismatch otherwise).
  int64_t get_int_in(const std::string& name, int64_t low, int64_t high) const {
    const int64_t v = get_int(name);
    if (v < low || v > high)
      throw StateMismatch("checkpoint state '" + prefix_ + name + "' is " + std::to_string(v) +
                          ", outside [" + std::to_string(low) + ", " + std::to_string(high) + "]");
    return v;
  }
  // A counter (steps, episodes, the step something is next due): in [0, high].
  int64_t get_count(const std::string& name, int64_t high = INT64_MAX) const {
    return get_int_in(name, 0, high);
  }
  double get_double(const std::string& name) const { return get_span<double>(name, 1)[0]; }
  bool get_bool(const std::string& name) const { return get_int(name) != 0; }

  // The stored values; `expected_size` >= 0 is checked.
  template <class T>
  std::vector<T> get_span(const std::string& name, int64_t expected_size = -1) const {
    const Tensor& t = find(name, dtype_of<T>());
    if (t.shape.size() != 1 || (expected_size >= 0 && t.shape[0] != expected_size))
      throw StateMismatch("checkpoint state '" + prefix_ + name + "' has " +
                          std::to_string(t.numel()) + " values, expected " +
                          std::to_string(expected_size));
    std::vector<T> values(static_cast<size_t>(t.shape[0]));
    if (!values.empty()) std::memcpy(values.data(), t.bytes.data(), values.size() * sizeof(T));
    return values;
  }
  template <class T>
  void get_into(const std::string& name, std::span<T> out) const {
    const std::vector<T> values = get_span<T>(name, static_cast<int64_t>(out.size()));
    std::copy(values.begin(), values.end(), out.begin());
  }

  std::string get_string(const std::string& name) const {
    const std::vector<int64_t> bytes = get_span<int64_t>(name);
    return std::string(bytes.begin(), bytes.end());
  }

  void get_rng(const std::string& name, Rng& rng) const {
    const std::vector<uint64_t> w = get_span<uint64_t>(name, 6);
    Rng::State s;
    for (int i = 0; i < 4; ++i) s.s[i] = w[i];
    s.has_spare_normal = w[4] != 0;
    s.spare_normal = std::bit_cast<double>(w[5]);
    rng.set_state(s);
  }

  // The stored tensor (rlrun's Eigen helpers read matrices through it).
  const Tensor& find(const std::string& name, DType dtype) const {
    const auto it = tensors_.find(prefix_ + name);
    if (it == tensors_.end())
      throw StateMismatch("checkpoint has no state '" + prefix_ + name +
                          "' (written by another configuration or rlrun version?)");
    if (it->second.dtype != dtype)
      throw StateMismatch("checkpoint state '" + prefix_ + name + "' has another dtype");
    return it->second;
  }
  const TensorMap& tensors() const { return tensors_; }

 private:
  const TensorMap& tensors_;
  std::string prefix_;
};

}  // namespace rlrun
