// rlrun's samplers on standard test functions, for scripts/bench/tpe.sh, which runs Optuna's
// samplers on the same functions (scripts/bench/tpe.py) and compares the two.
//
//   rlrun_tpe_bench [--seeds N] [--trials T] [--samplers tpe,random,tpe_univariate]
//                   [--functions branin,hartmann6,noisy_quad]
//
// prints one line per (function, sampler, seed): "function<TAB>sampler<TAB>seed<TAB>best",
// where best is the true objective value of the best trial found. Functions (minimised):
//  * branin:     Branin-Hoo on [-5, 10] x [0, 15], minimum 0.397887;
//  * hartmann6:  Hartmann 6-D on [0, 1]^6, minimum -3.32237;
//  * noisy_quad: sum_i (x_i - 0.3)^2 on [-1, 1]^4, observed with N(0, 0.01^2) noise; the best
//    *observed* trial's noise-free value is reported (what a user would pick and get).
// The definitions are the usual ones (Surjanovic & Bingham's Virtual Library of Simulation
// Experiments); scripts/bench/tpe.py writes them the same way.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "mini_study.hpp"
#include "rlrun/rng.hpp"
#include "rlrun/tune/random_sampler.hpp"
#include "rlrun/tune/tpe_sampler.hpp"

using namespace rlrun::tune;

namespace {

struct Evaluation {
  double observed;  // what the study is told
  double truth;     // the noise-free value
};

// A test function: asks its parameters from the study, returns observed and true values.
using Objective = std::function<Evaluation(MiniStudy&, rlrun::Rng& noise)>;

Distribution uniform(const std::string& name, double low, double high) {
  return make_float_distribution(name, low, high, false, std::nullopt);
}

// x0, x1, ... (spelt out: GCC 12 warns falsely about "x" + std::to_string(j), -Wrestrict).
const std::string kNames[6] = {"x0", "x1", "x2", "x3", "x4", "x5"};

Evaluation branin(MiniStudy& study, rlrun::Rng&) {
  static const Distribution d1 = uniform("x1", -5, 10), d2 = uniform("x2", 0, 15);
  const double x1 = study.suggest("x1", d1), x2 = study.suggest("x2", d2);
  const double b = 5.1 / (4 * M_PI * M_PI), c = 5 / M_PI, t = 1 / (8 * M_PI);
  const double v = std::pow(x2 - b * x1 * x1 + c * x1 - 6, 2) + 10 * (1 - t) * std::cos(x1) + 10;
  return {v, v};
}

Evaluation hartmann6(MiniStudy& study, rlrun::Rng&) {
  static const double alpha[4] = {1.0, 1.2, 3.0, 3.2};
  static const double a[4][6] = {{10, 3, 17, 3.5, 1.7, 8},
                                 {0.05, 10, 17, 0.1, 8, 14},
                                 {3, 3.5, 1.7, 10, 17, 8},
                                 {17, 8, 0.05, 10, 0.1, 14}};
  static const double p[4][6] = {{1312, 1696, 5569, 124, 8283, 5886},
                                 {2329, 4135, 8307, 3736, 1004, 9991},
                                 {2348, 1451, 3522, 2883, 3047, 6650},
                                 {4047, 8828, 8732, 5743, 1091, 381}};
  static const std::vector<Distribution> d = {uniform("x0", 0, 1), uniform("x1", 0, 1),
                                              uniform("x2", 0, 1), uniform("x3", 0, 1),
                                              uniform("x4", 0, 1), uniform("x5", 0, 1)};
  double x[6];
  for (int j = 0; j < 6; ++j) x[j] = study.suggest(kNames[j], d[j]);
  double v = 0;
  for (int i = 0; i < 4; ++i) {
    double inner = 0;
    for (int j = 0; j < 6; ++j) inner += a[i][j] * std::pow(x[j] - p[i][j] * 1e-4, 2);
    v -= alpha[i] * std::exp(-inner);
  }
  return {v, v};
}

Evaluation noisy_quad(MiniStudy& study, rlrun::Rng& noise) {
  static const std::vector<Distribution> d = {uniform("x0", -1, 1), uniform("x1", -1, 1),
                                              uniform("x2", -1, 1), uniform("x3", -1, 1)};
  double v = 0;
  for (int j = 0; j < 4; ++j) v += std::pow(study.suggest(kNames[j], d[j]) - 0.3, 2);
  return {v + 0.01 * noise.normal(), v};
}

// One study: the true value of the trial with the best observed value.
double run_study(Sampler& sampler, uint64_t seed, int n_trials, const Objective& objective) {
  MiniStudy study(sampler, seed);
  rlrun::Rng noise(seed ^ 0x243f6a8885a308d3ULL);
  double best_observed = INFINITY, best_truth = INFINITY;
  for (int t = 0; t < n_trials; ++t) {
    study.ask();
    const Evaluation e = objective(study, noise);
    study.tell(e.observed);
    if (e.observed < best_observed) {
      best_observed = e.observed;
      best_truth = e.truth;
    }
  }
  return best_truth;
}

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) out.push_back(item);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  int seeds = 20, trials = 100;
  std::vector<std::string> samplers = {"tpe", "random"};
  std::vector<std::string> wanted = {"branin", "hartmann6", "noisy_quad"};
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--seeds")
      seeds = std::atoi(value.c_str());
    else if (flag == "--trials")
      trials = std::atoi(value.c_str());
    else if (flag == "--samplers")
      samplers = split(value);
    else if (flag == "--functions")
      wanted = split(value);
    else {
      std::fprintf(stderr,
                   "usage: rlrun_tpe_bench [--seeds N] [--trials T] [--samplers "
                   "tpe,random,tpe_univariate] [--functions branin,hartmann6,noisy_quad]\n");
      return 2;
    }
  }
  const std::vector<std::pair<std::string, Objective>> functions = {
      {"branin", branin}, {"hartmann6", hartmann6}, {"noisy_quad", noisy_quad}};
  for (const auto& [function, objective] : functions) {
    if (std::find(wanted.begin(), wanted.end(), function) == wanted.end()) continue;
    for (const std::string& name : samplers) {
      const auto start = std::chrono::steady_clock::now();
      for (int seed = 0; seed < seeds; ++seed) {
        std::unique_ptr<Sampler> sampler;
        if (name == "tpe") {
          sampler = std::make_unique<TpeSampler>();
        } else if (name == "tpe_univariate") {
          TpeConfig config;
          config.multivariate = false;
          sampler = std::make_unique<TpeSampler>(config);
        } else if (name == "random") {
          sampler = std::make_unique<RandomSampler>();
        } else {
          std::fprintf(stderr, "unknown sampler '%s'\n", name.c_str());
          return 2;
        }
        const double best = run_study(*sampler, static_cast<uint64_t>(seed), trials, objective);
        std::printf("%s\t%s\t%d\t%.10g\n", function.c_str(), name.c_str(), seed, best);
      }
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::fprintf(stderr, "%s %s: %d studies of %d trials in %.2f s\n", function.c_str(),
                   name.c_str(), seeds, trials, seconds);
    }
  }
  return 0;
}
