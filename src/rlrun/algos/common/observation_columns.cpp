#include "rlrun/algos/common/observation_columns.hpp"

#include <algorithm>

#include "rlrun/core/pixel_byte.hpp"

namespace rlrun {

namespace {

// Whether the values of `space` (a Box or one key of a Dict) are stored as bytes.
bool stored_as_bytes(const Space& space) { return space.is_uint8_box(); }

}  // namespace

void ObservationColumns::add_run(int count, bool bytes) {
  if (count == 0) return;
  if (!runs_.empty() && runs_.back().bytes == bytes) {
    runs_.back().count += count;
  } else {
    int at = 0;
    for (const Run& r : runs_)
      if (r.bytes == bytes) at += r.count;
    runs_.push_back({rows_, count, at, bytes});
  }
  rows_ += count;
}

ObservationColumns::ObservationColumns(const Space& space, int64_t columns) {
  if (space.is_dict()) {
    for (const Space& key : space.subspaces()) add_run(key.flat_dim(), stored_as_bytes(key));
  } else {
    add_run(space.flat_dim(), stored_as_bytes(space));
  }
  int float_rows = 0, byte_rows = 0;
  for (const Run& r : runs_) (r.bytes ? byte_rows : float_rows) += r.count;
  floats_.resize(float_rows, columns);
  bytes_.resize(byte_rows, columns);
}

double ObservationColumns::bytes_per_observation(const Space& space) {
  if (!space.is_dict()) return space.flat_dim() * (stored_as_bytes(space) ? 1.0 : sizeof(float));
  double total = 0;
  for (const Space& key : space.subspaces()) total += bytes_per_observation(key);
  return total;
}

void ObservationColumns::set_mixed(int64_t column, const float* obs) {
  for (const Run& r : runs_) {
    if (!r.bytes) {
      std::copy_n(obs + r.begin, r.count, floats_.col(column).data() + r.at);
      continue;
    }
    std::transform(obs + r.begin, obs + r.begin + r.count, bytes_.col(column).data() + r.at,
                   pixel_byte);
  }
}

void ObservationColumns::get(int64_t column, int begin, int count, float* out) const {
  const int end = begin + count;
  for (const Run& r : runs_) {
    const int from = std::max(begin, r.begin), to = std::min(end, r.begin + r.count);
    if (from >= to) continue;
    const int skip = from - r.begin;
    float* dst = out + (from - begin);
    if (!r.bytes) {
      std::copy_n(floats_.col(column).data() + r.at + skip, to - from, dst);
      continue;
    }
    const uint8_t* src = bytes_.col(column).data() + r.at + skip;
    for (int i = 0; i < to - from; ++i) dst[i] = static_cast<float>(src[i]);
  }
}

void ObservationColumns::write_state(StateWriter& out, const std::string& name,
                                     int64_t used) const {
  if (floats_.rows() > 0 || bytes_.rows() == 0) put_matrix(out, name, floats_.leftCols(used));
  if (bytes_.rows() > 0) put_matrix(out, name + "_uint8", bytes_.leftCols(used));
}

void ObservationColumns::read_state(const StateReader& in, const std::string& name, int64_t used) {
  if (floats_.rows() > 0 || bytes_.rows() == 0) get_matrix(in, name, floats_.leftCols(used));
  if (bytes_.rows() > 0) get_matrix(in, name + "_uint8", bytes_.leftCols(used));
}

}  // namespace rlrun
