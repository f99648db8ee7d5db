// TPESampler end to end through the bench's minimal study loop (bench/mini_study.hpp):
// random start-up, reproducibility per (seed, trial number), conditional parameters, and that
// it actually optimises — better than random search on a quadratic.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <vector>

#include "mini_study.hpp"
#include "rlrun/tune/random_sampler.hpp"
#include "rlrun/tune/tpe_sampler.hpp"

using namespace rlrun::tune;

namespace {

const Distribution kX = make_float_distribution("x", -5, 5, false, std::nullopt);
const Distribution kY = make_float_distribution("y", -5, 5, false, std::nullopt);

// (x - 1)^2 + (y + 2)^2, minimum 0 at (1, -2).
double quadratic(MiniStudy& study) {
  const double x = study.suggest("x", kX), y = study.suggest("y", kY);
  return (x - 1) * (x - 1) + (y + 2) * (y + 2);
}

double best_of(Sampler& sampler, uint64_t seed, int n_trials,
               const std::function<double(MiniStudy&)>& objective) {
  MiniStudy study(sampler, seed);
  double best = INFINITY;
  for (int t = 0; t < n_trials; ++t) {
    study.ask();
    const double value = objective(study);
    study.tell(value);
    best = std::min(best, value);
  }
  return best;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

TEST_CASE("tpe sampler: random until n_startup_trials trials finished", "[tune]") {
  TpeSampler tpe;
  MiniStudy study(tpe, 1);
  for (int t = 0; t < 10; ++t) {
    study.ask();
    // Before 10 finished trials there is nothing to learn from: no relative space or sample.
    if (t == 0) CHECK(study.relative_space().empty());
    quadratic(study);
    study.tell(1.0);
  }
  study.ask();
  CHECK(study.relative_space().size() == 2);
  // The 11th trial is TPE's: a fresh sampler reseeded for it, with the same history, draws the
  // same values as sample_relative did.
  TpeSampler again;
  again.reseed(1, 10);
  const auto relative = again.sample_relative(study.view(), study.relative_space());
  REQUIRE(relative.size() == 2);
  CHECK(study.suggest("x", kX) == relative.at("x"));
  CHECK(study.suggest("y", kY) == relative.at("y"));
}

TEST_CASE("tpe sampler: same seed and history give the same trials, another seed not", "[tune]") {
  auto run = [](uint64_t seed) {
    TpeSampler tpe;
    MiniStudy study(tpe, seed);
    for (int t = 0; t < 25; ++t) {
      study.ask();
      study.tell(quadratic(study));
    }
    std::vector<double> xs;
    for (const auto& trial : study.trials()) xs.push_back(trial.params.at("x"));
    return xs;
  };
  const auto a = run(3);
  CHECK(run(3) == a);
  CHECK(run(4) != a);
}

TEST_CASE("tpe sampler: conditional parameters are sampled over the trials that have them",
          "[tune]") {
  // Branch "a" asks x in [-5, 5] (best at x = 2), branch "b" asks k in 0..20 (best at 15);
  // "a" can reach 0, "b" at best 0.5. lr is asked in every trial.
  const Distribution kind = make_categorical_distribution("kind", {"a", "b"});
  const Distribution k_dist = make_int_distribution("k", 0, 20, false, 1);
  const Distribution lr = make_float_distribution("lr", 1e-4, 1e-1, true, std::nullopt);
  auto objective = [&](MiniStudy& s) {
    const double penalty = std::pow(std::log10(s.suggest("lr", lr)) + 2.0, 2);  // best 1e-2
    if (s.suggest("kind", kind) == 0) {
      const double x = s.suggest("x", kX);
      return (x - 2) * (x - 2) + penalty;
    }
    const double k = s.suggest("k", k_dist);
    return 0.5 + (k - 15) * (k - 15) / 10 + penalty;
  };
  TpeSampler tpe;
  MiniStudy study(tpe, 5);
  std::vector<double> late_x;
  for (int t = 0; t < 80; ++t) {
    study.ask();
    const double value = objective(study);
    study.tell(value);
    const auto& trial = study.trials().back();
    for (const auto& [name, value_internal] : trial.params)
      REQUIRE(contains(trial.distributions.at(name), value_internal));
    if (t >= 40 && trial.params.count("x")) late_x.push_back(trial.params.at("x"));
  }
  // The joint space is what every trial asked: kind and lr; x and k fall out.
  const SearchSpace joint = tpe.infer_relative_search_space(study.view());
  CHECK(joint.size() == 2);
  CHECK(joint.count("kind"));
  CHECK(joint.count("lr"));
  // Independent TPE on x learnt where branch "a" is good, and TPE prefers branch "a".
  REQUIRE(late_x.size() >= 20);
  CHECK(std::fabs(median(late_x) - 2.0) < 0.5);
  double best = INFINITY;
  for (const auto& trial : study.trials()) best = std::min(best, *trial.value());
  CHECK(best < 0.1);
}

TEST_CASE("tpe sampler: beats random search on a 2-D quadratic (60 trials, 10 seeds)", "[tune]") {
  std::vector<double> tpe_best, uni_best, random_best;
  TpeConfig univariate;
  univariate.multivariate = false;
  for (uint64_t seed = 0; seed < 10; ++seed) {
    TpeSampler tpe;
    TpeSampler tpe_uni(univariate);
    RandomSampler random;
    tpe_best.push_back(best_of(tpe, seed, 60, quadratic));
    uni_best.push_back(best_of(tpe_uni, seed, 60, quadratic));
    random_best.push_back(best_of(random, seed, 60, quadratic));
  }
  INFO("median best: TPE " << median(tpe_best) << ", univariate TPE " << median(uni_best)
                           << ", random " << median(random_best));
  // Random search's median best over 60 draws in a 10 x 10 box is about 100 ln 2 / (60 pi)
  // ~ 0.37; TPE should be several times closer.
  CHECK(median(tpe_best) < 0.25 * median(random_best));
  CHECK(median(uni_best) < 0.25 * median(random_best));
}

TEST_CASE("tpe sampler: one step's l and g match Optuna's on a study with pruned trials",
          "[tune]") {
  // The study of the "tpe step" section of tests/tune/optuna_reference.py (maximised; trials 4
  // and 9 pruned; c asked in every third trial); the expected numbers are what Optuna 3.1's
  // _get_observation_pairs, _split_observation_pairs and _ParzenEstimator give on it (Debian's
  // python3-optuna 3.1.0).
  const Distribution dx = make_float_distribution("x", -5, 5, false, std::nullopt);
  const Distribution dn = make_int_distribution("n", 1, 64, true, 1);
  const Distribution dc = make_categorical_distribution("c", {"a", "b", "c"});
  const int ns[7] = {1, 2, 4, 8, 16, 32, 64};
  std::vector<FrozenTrial> trials;
  for (int i = 0; i < 14; ++i) {
    FrozenTrial t;
    t.number = i;
    const double x = std::round((-4.5 + 0.7 * i) * 1000) / 1000;
    const double n = ns[(3 * i) % 7];
    t.params = {{"x", x}, {"n", n}};
    t.distributions = {{"x", dx}, {"n", dn}};
    if (i % 3 == 0) {
      t.params["c"] = i % 2 * 2;
      t.distributions["c"] = dc;
    }
    const double value = -(x - 1) * (x - 1) - 0.1 * std::fabs(std::log2(n) - 3);
    if (i == 4 || i == 9) {
      t.state = TrialState::kPruned;
      for (int s = 1; s <= i / 3; ++s) t.intermediate_values[s] = value - 0.1 * (i / 3 - s);
    } else {
      t.state = TrialState::kComplete;
      t.values = std::vector<double>{value};
    }
    trials.push_back(t);
  }
  const StudyView study{StudyDirection::kMaximize, trials};
  TpeSampler tpe;
  const SearchSpace space = tpe.infer_relative_search_space(study);
  REQUIRE(space.size() == 2);
  REQUIRE(space.count("n"));
  REQUIRE(space.count("x"));

  auto check_all = [](const std::vector<double>& got, const std::vector<double>& expected) {
    REQUIRE(got.size() == expected.size());
    for (size_t i = 0; i < got.size(); ++i) CHECK(got[i] == Approx(expected[i]).epsilon(1e-10));
  };
  const auto fitted = tpe.fit(study, space);
  REQUIRE(fitted);
  // Below: trials 7 and 8 (gamma(14) = 2; the pruned trial 9 ranks after every complete one).
  check_all(fitted->below.weights(), {1.0 / 3, 1.0 / 3, 1.0 / 3});
  check_all(fitted->below.dimension("n").mus, {0.0, 2.0794415416798357, 1.7367590216208906});
  check_all(fitted->below.dimension("n").sigmas,
            {1.214953101090418, 1.214953101090418, 4.859812404361672});
  check_all(fitted->below.dimension("x").mus, {0.4, 1.1, 0.0});
  check_all(fitted->below.dimension("x").sigmas, {2.5, 2.5, 10.0});
  check_all(fitted->above.weights(), std::vector<double>(13, 1.0 / 13));
  check_all(fitted->above.dimension("x").mus,
            {-4.5, -3.8, -3.1, -2.4, -1.7, -1.0, -0.3, 1.8, 2.5, 3.2, 3.9, 4.6, 0.0});
  std::vector<double> above_n_sigmas(12, 0.6423710495211826);
  above_n_sigmas.push_back(4.859812404361672);
  check_all(fitted->above.dimension("n").sigmas, above_n_sigmas);
  std::vector<double> above_x_sigmas(12, 1.3218021521667294);
  above_x_sigmas.push_back(10.0);
  check_all(fitted->above.dimension("x").sigmas, above_x_sigmas);
  const Observations points = {{"n", {1, 8, 50}}, {"x", {1.0, -4.0, 3.3}}};
  const auto log_l = fitted->below.log_pdf(points), log_g = fitted->above.log_pdf(points);
  check_all({log_l[0] - log_g[0], log_l[1] - log_g[1], log_l[2] - log_g[2]},
            {1.6552698699989328, 1.2796326214978953, 1.190739912797563});

  // The conditional c: no trial of the below set has it (l is the prior alone); g has trials
  // 0, 3, 6, 9 (pruned), 12.
  const auto conditional = tpe.fit(study, {{"c", dc}});
  REQUIRE(conditional);
  check_all(conditional->below.dimension("c").categorical_weights, {1.0 / 3, 1.0 / 3, 1.0 / 3});
  CHECK(conditional->above.weights().size() == 6);
  const Observations choices = {{"c", {0, 1, 2}}};
  const auto cl = conditional->below.log_pdf(choices), cg = conditional->above.log_pdf(choices);
  check_all({cl[0] - cg[0], cl[1] - cg[1], cl[2] - cg[2]},
            {-0.36772478012531706, 0.8109302162163285, -0.10536051565782634});
}
