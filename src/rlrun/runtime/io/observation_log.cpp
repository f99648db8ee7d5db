#include "rlrun/runtime/io/observation_log.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/npy.hpp"

namespace rlrun {

namespace {

namespace fs = std::filesystem;

// Natural order: digit runs compare as numbers ("obs_2" < "obs_10").
bool natural_less(const std::string& a, const std::string& b) {
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) &&
        std::isdigit(static_cast<unsigned char>(b[j]))) {
      size_t i_end = i, j_end = j;
      while (i_end < a.size() && std::isdigit(static_cast<unsigned char>(a[i_end]))) ++i_end;
      while (j_end < b.size() && std::isdigit(static_cast<unsigned char>(b[j_end]))) ++j_end;
      std::string x = a.substr(i, i_end - i), y = b.substr(j, j_end - j);
      x.erase(0, std::min(x.find_first_not_of('0'), x.size()));
      y.erase(0, std::min(y.find_first_not_of('0'), y.size()));
      if (x.size() != y.size()) return x.size() < y.size();
      if (x != y) return x < y;
      i = i_end;
      j = j_end;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

}  // namespace

std::vector<std::string> observation_log_files(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw UsageError("observation log " + path + " does not exist");
  if (!fs::is_directory(path, ec)) return {path};
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(path, ec))
    if (entry.is_regular_file() && entry.path().extension() == ".npy")
      names.push_back(entry.path().filename().string());
  if (names.empty()) throw UsageError("observation log directory " + path + " holds no .npy file");
  std::sort(names.begin(), names.end(), natural_less);
  std::vector<std::string> files;
  for (const auto& n : names) files.push_back((fs::path(path) / n).string());
  return files;
}

ObservationChunk read_observation_chunk(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw UsageError("cannot read observation log " + file);
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  Tensor t;
  try {
    t = decode_npy(bytes, file);
  } catch (const std::exception& e) {
    throw UsageError(e.what());
  }
  ObservationChunk chunk;
  if (t.shape.size() == 2) {
    chunk.rows = t.shape[0];
    chunk.obs_dim = static_cast<int>(t.shape[1]);
  } else if (t.shape.size() == 1) {
    chunk.rows = t.shape[0];
    chunk.obs_dim = 1;
  } else {
    throw UsageError(file + ": an observation log chunk has shape (steps, obs_dim), this one has " +
                     std::to_string(t.shape.size()) + " dimensions");
  }
  chunk.values.resize(static_cast<size_t>(t.numel()));
  if (t.dtype == DType::kFloat32) {
    std::copy_n(t.data<float>(), chunk.values.size(), chunk.values.begin());
  } else if (t.dtype == DType::kFloat64) {
    std::transform(t.data<double>(), t.data<double>() + chunk.values.size(), chunk.values.begin(),
                   [](double v) { return static_cast<float>(v); });
  } else {
    throw UsageError(file + ": observation log chunks hold float32 (or float64) values");
  }
  return chunk;
}

}  // namespace rlrun
