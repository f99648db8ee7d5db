#pragma once
// Observations kept one per column, with the values of uint8 Boxes stored as bytes: SB3's
// ReplayBuffer allocates its observations with the space's dtype
// (stable_baselines3/common/buffers.py, `np.zeros(..., dtype=observation_space.dtype)`), so a
// 4x84x84 uint8 frame takes 28 KB of memory, not the 113 KB of float32. Values come in and go
// out as float32 (rlrun's one observation type); a uint8 Box holds whole numbers 0-255, which
// a byte keeps exactly. A Dict stores each key by its own dtype.
#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "rlrun/core/state_dict.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

class ObservationColumns {
 public:
  ObservationColumns() = default;
  ObservationColumns(const Space& space, int64_t columns);

  // The memory one observation of `space` takes here.
  static double bytes_per_observation(const Space& space);

  int rows() const { return rows_; }
  // The memory the columns take.
  int64_t bytes() const {
    return floats_.size() * static_cast<int64_t>(sizeof(float)) + bytes_.size();
  }

  // Column `column` = `obs` (rows() floats).
  void set(int64_t column, const float* obs) {
    if (bytes_.rows() == 0)  // all float32: a plain copy (PPO's minibatches gather many)
      std::copy_n(obs, rows_, floats_.data() + column * rows_);
    else
      set_mixed(column, obs);
  }
  // rows [begin, begin + count) of column `column` into `out`.
  void get(int64_t column, int begin, int count, float* out) const;
  void get(int64_t column, float* out) const {
    if (bytes_.rows() == 0)
      std::copy_n(floats_.data() + column * rows_, rows_, out);
    else
      get(column, 0, rows_, out);
  }

  // The first `used` columns, as `name` (float rows) and `name`_uint8 (byte rows); a space
  // without uint8 Boxes writes exactly what a float32 matrix of observations did.
  void write_state(StateWriter& out, const std::string& name, int64_t used) const;
  void read_state(const StateReader& in, const std::string& name, int64_t used);

 private:
  // A stretch of rows of one dtype: rows [begin, begin + count) of an observation are rows
  // [at, at + count) of floats_ or bytes_.
  struct Run {
    int begin = 0, count = 0, at = 0;
    bool bytes = false;
  };
  void add_run(int count, bool bytes);
  void set_mixed(int64_t column, const float* obs);

  std::vector<Run> runs_;
  int rows_ = 0;
  Eigen::MatrixXf floats_;
  Eigen::Matrix<uint8_t, Eigen::Dynamic, Eigen::Dynamic> bytes_;
};

}  // namespace rlrun
