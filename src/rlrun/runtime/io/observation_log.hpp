#pragma once
// Reading observation logs (the obs_log training callback, runtime/run/obs_log_callback.hpp):
// .npy chunks of float32 (rows = steps, columns = observation values), C order, read with
// core/npy.hpp. `rlrun record --from-obs` turns them into video.
#include <cstdint>
#include <string>
#include <vector>

namespace rlrun {

// A single .npy file, or a directory's *.npy files in natural name order (obs_2 before
// obs_10; the callback's zero-padded names sort the same either way). Throws UsageError when
// the path does not exist or holds no .npy file.
std::vector<std::string> observation_log_files(const std::string& path);

struct ObservationChunk {
  std::vector<float> values;  // rows * obs_dim, row-major
  int64_t rows = 0;
  int obs_dim = 0;
};

// Accepts float32 or float64 arrays of shape (rows, obs_dim), or (rows,) as obs_dim 1.
// Throws UsageError naming the file on anything else.
ObservationChunk read_observation_chunk(const std::string& file);

}  // namespace rlrun
