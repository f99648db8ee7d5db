#include "rlrun/runtime/io/tensorboard/learning_curve_image.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "rlrun/core/private_temp_dir.hpp"
#include "rlrun/render/learning_curves.hpp"
#include "rlrun/runtime/io/run_results.hpp"

namespace rlrun {

namespace {

// (step, value) where both are finite.
std::vector<std::pair<double, double>> points(const RunResult& run, const std::string& key) {
  std::vector<std::pair<double, double>> out;
  const auto steps = run.progress.find("time/total_timesteps");
  const auto values = run.progress.find(key);
  if (steps == run.progress.end() || values == run.progress.end()) return out;
  for (size_t i = 0; i < steps->second.size() && i < values->second.size(); ++i)
    if (std::isfinite(steps->second[i]) && std::isfinite(values->second[i]))
      out.emplace_back(steps->second[i], values->second[i]);
  return out;
}

}  // namespace

std::string learning_curve_png(const std::string& run_dir, const std::string& title) {
  const RunResult run = read_run(run_dir);
  std::vector<CurveGroup> groups;
  const auto training = points(run, "rollout/ep_rew_mean");
  if (training.size() < 2) return "";
  groups.push_back({"training (last 100 episodes)", {training}});
  const auto evaluation = points(run, "eval/mean_reward");
  if (evaluation.size() >= 2) groups.push_back({"evaluation", {evaluation}});
  const PrivateTempDir scratch("rlrun-tensorboard-");
  const std::string path = scratch.file("learning_curve.png");
  plot_learning_curves(groups, "mean episode return", title, path);
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

}  // namespace rlrun
