// embed_policy MODEL [OBS.f32 ACTIONS.f32 | --latency N]
// Loads a trained rlrun model with rlrun::Policy (include/rlrun/policy.hpp) and acts:
// with two files, on every observation in OBS.f32 (float32, observation_size() per step),
// writing the actions to ACTIONS.f32; with --latency N, times N single-observation act() calls
// and prints the median and 99th percentile in microseconds (scripts/bench/deploy.sh);
// otherwise on an all-zero observation, printed.
#include <rlrun/policy.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

namespace {

int latency(const rlrun::Policy& policy, int calls) {
  std::vector<float> obs(policy.observation_size()), action(policy.action_size());
  std::vector<double> micros;
  micros.reserve(static_cast<size_t>(calls));
  for (int k = 0; k < calls + 1000; ++k) {  // the first 1000 calls warm up
    for (size_t i = 0; i < obs.size(); ++i) obs[i] = 0.1f * std::sin(static_cast<float>(k + i));
    const auto start = std::chrono::steady_clock::now();
    policy.act(obs, action);
    const auto end = std::chrono::steady_clock::now();
    if (k >= 1000) micros.push_back(std::chrono::duration<double, std::micro>(end - start).count());
  }
  std::sort(micros.begin(), micros.end());
  std::printf("rlrun::Policy::act %s %s: p50 %.2f us, p99 %.2f us over %d calls\n",
              policy.algorithm().c_str(), policy.env_id().c_str(), micros[micros.size() / 2],
              micros[micros.size() * 99 / 100], calls);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 && argc != 4) {
    std::fprintf(stderr, "usage: %s MODEL [OBS.f32 ACTIONS.f32 | --latency N]\n", argv[0]);
    return 2;
  }
  try {
    const rlrun::Policy policy = rlrun::Policy::load(argv[1]);
    if (argc == 4 && std::string(argv[2]) == "--latency")
      return latency(policy, std::max(1, std::atoi(argv[3])));
    std::vector<float> obs(policy.observation_size()), action(policy.action_size());
    if (argc == 2) {
      policy.act(obs, action);
      std::printf("%s policy for %s: %zu observation floats -> action", policy.algorithm().c_str(),
                  policy.env_id().c_str(), obs.size());
      for (float a : action) std::printf(" %g", static_cast<double>(a));
      std::printf("\n");
      return 0;
    }
    std::ifstream in(argv[2], std::ios::binary);
    std::ofstream out(argv[3], std::ios::binary);
    const auto obs_bytes = static_cast<std::streamsize>(obs.size() * sizeof(float));
    while (in.read(reinterpret_cast<char*>(obs.data()), obs_bytes)) {
      policy.act(obs, action);
      out.write(reinterpret_cast<const char*>(action.data()),
                static_cast<std::streamsize>(action.size() * sizeof(float)));
    }
    return out ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "embed_policy: %s\n", e.what());
    return 1;
  }
}
