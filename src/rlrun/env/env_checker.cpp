#include "rlrun/env/env_checker.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>

#include "rlrun/env/random_actions.hpp"
#include "rlrun/env/space_text.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {

namespace {

using Obs = std::vector<float>;

// Bitwise equality, so that NaN == NaN and -0 != +0 (Gymnasium's data_equivalence(exact=True)).
bool identical(std::span<const float> a, std::span<const float> b) {
  // memcmp's pointers must not be null, even for 0 bytes (an empty vector's data() may be).
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

// Keys are only ever added (an env may declare one when it first reports it, as Python envs
// do): values of the keys both records know must be bit-identical, the others absent.
bool identical_values(const std::vector<double>& a, const std::vector<double>& b) {
  const size_t common = std::min(a.size(), b.size());
  if (common > 0 && std::memcmp(a.data(), b.data(), common * sizeof(double)) != 0) return false;
  const std::vector<double>& longer = a.size() > b.size() ? a : b;
  for (size_t i = common; i < longer.size(); ++i)
    if (!std::isnan(longer[i])) return false;
  return true;
}

class Checker {
 public:
  Checker(Env& env, uint64_t seed, int steps) : env_(env), seed_(seed), steps_(steps) {}

  std::vector<std::string> run() {
    if (!check_spaces()) return problems_;
    try {
      check_reset_seeding();
      check_trajectory_determinism();
    } catch (const std::exception& e) {
      problem("the env threw during " + phase_ + ": " + e.what());
    }
    return problems_;
  }

 private:
  // One recorded step, for comparing two rollouts.
  struct Record {
    Obs obs;
    double reward;
    bool terminated, truncated;
    std::vector<double> info;
  };

  void problem(std::string message) {
    // The same defect tends to repeat every step; report each message once.
    for (const auto& p : problems_)
      if (p == message) return;
    problems_.push_back(std::move(message));
  }

  bool check_spaces() {
    const Space& obs_space = env_.observation_space();
    const Space& act_space = env_.action_space();
    if (obs_space.flat_dim() <= 0) problem("observation_space has no elements");
    if (act_space.flat_dim() <= 0) problem("action_space has no elements");
    for (const Space* s : {&obs_space, &act_space}) {
      std::vector<const Space*> parts{s};
      for (const Space& key : s->subspaces()) parts.push_back(&key);  // a Dict's keys
      for (const Space* part : parts)
        if (part->is_box())
          for (size_t i = 0; i < part->low().size(); ++i)
            if (!(part->low()[i] <= part->high()[i]))
              problem("space " + part->describe() + " has low > high at index " +
                      std::to_string(i));
    }
    return problems_.empty();
  }

  // The observation as text, a Dict key by key.
  std::string format(std::span<const float> x) const {
    return format_value(env_.observation_space(), x);
  }
  // " (key 'row' is 7, not in Discrete(4))": which part of an observation is outside.
  std::string why_outside(std::span<const float> x) const {
    const std::string why = outside_reason(env_.observation_space(), x);
    return why.empty() ? "" : " (" + why + ")";
  }

  // Several agents (include/rlrun/env.hpp): observations and actions hold every agent's,
  // agent-major; each agent's part must be inside the space.
  int agents() const { return std::max(1, env_.num_agents()); }
  size_t obs_size() const {
    return static_cast<size_t>(env_.observation_space().flat_dim()) * agents();
  }
  void check_inside(const Obs& obs, const std::string& what) {
    const size_t dim = static_cast<size_t>(env_.observation_space().flat_dim());
    for (int a = 0; a < agents(); ++a) {
      const std::span<const float> part(obs.data() + a * dim, dim);
      if (!env_.observation_space().contains(part))
        problem("the observation returned by " + what + " " + format(part) + " is not inside " +
                env_.observation_space().describe() + why_outside(part) +
                (agents() > 1 ? " (agent " + std::to_string(a) + ")" : std::string()));
    }
  }

  Obs reset(std::optional<uint64_t> seed, const char* what) {
    Obs obs(obs_size());
    phase_ = what;
    env_.reset(seed, obs);
    check_inside(obs, what);
    return obs;
  }

  void check_reset_seeding() {
    const Obs a1 = reset(seed_, "reset(seed)");
    const Obs a2 = reset(std::nullopt, "reset()");
    const Obs a3 = reset(std::nullopt, "reset()");
    const Obs b1 = reset(seed_, "reset(seed)");
    const Obs b2 = reset(std::nullopt, "reset()");
    const Obs b3 = reset(std::nullopt, "reset()");
    if (!identical(a1, b1))
      problem("reset(seed) is not deterministic: " + format(a1) + " then " + format(b1));
    else if (!identical(a2, b2) || !identical(a3, b3))
      problem("reset() after reset(seed) is not deterministic (the env's RNG stream differs)");

    // A different seed must change the resets, unless the reset is not random at all (an env
    // may always start in the same state, e.g. a fixed maze). Three resets make a random
    // start that happens to repeat practically impossible.
    const Obs c1 = reset(seed_ + 1, "reset(seed + 1)");
    const Obs c2 = reset(std::nullopt, "reset()");
    const Obs c3 = reset(std::nullopt, "reset()");
    const bool random_start = !identical(a1, a2) || !identical(a2, a3);
    if (random_start && identical(a1, c1) && identical(a2, c2) && identical(a3, c3))
      problem("reset(seed) ignores the seed: seeds " + std::to_string(seed_) + " and " +
              std::to_string(seed_ + 1) + " give the same resets");
  }

  // Rolls out `steps_` steps from reset(seed_) with actions drawn from an Rng seeded with
  // seed_, resetting (without a seed) whenever an episode ends.
  std::vector<Record> rollout() {
    const Space& act_space = env_.action_space();
    Rng action_rng(seed_);
    const size_t act_dim = static_cast<size_t>(act_space.flat_dim());
    std::vector<float> action(act_dim * agents());
    std::vector<StepResult> results(static_cast<size_t>(agents()));
    RandomActions random_actions(act_space);  // legal ones when the env masks its actions
    std::vector<Record> records;
    records.reserve(steps_ + 1);
    Record first{reset(seed_, "reset(seed)"), 0.0, false, false, env_.info().values()};
    records.push_back(std::move(first));
    for (int t = 0; t < steps_; ++t) {
      random_actions.sample(env_.info(), agents(), action_rng, action);
      Record r{Obs(obs_size()), 0.0, false, false, {}};
      phase_ = "step() " + std::to_string(t);
      if (agents() == 1) {
        results[0] = env_.step(action, r.obs);
      } else {
        env_.step_agents(action, r.obs, results);
      }
      const StepResult result = results[0];
      const bool ended = result.terminated || result.truncated;
      r.reward = 0;
      for (const StepResult& each : results) {
        r.reward += each.reward;
        // Together, each with its own reason (one terminated, another truncated at the end).
        if ((each.terminated || each.truncated) != ended)
          problem("the agents did not end their episode together (step " + std::to_string(t) +
                  "): rlrun's multi-agent envs end all agents at once");
      }
      r.terminated = result.terminated;
      r.truncated = result.truncated;
      r.info = env_.info().values();
      check_inside(r.obs, "step() " + std::to_string(t));
      if (!std::isfinite(r.reward))
        problem("step() returned a non-finite reward " + std::to_string(r.reward) + " (step " +
                std::to_string(t) + ")");
      records.push_back(std::move(r));
      if (result.terminated || result.truncated) {
        // The new episode's first observation is part of the trajectory too.
        Obs first_obs = reset(std::nullopt, "reset() after the episode ended");
        records.push_back({std::move(first_obs), 0.0, false, false, env_.info().values()});
      }
    }
    return records;
  }

  void check_trajectory_determinism() {
    const std::vector<Record> a = rollout();
    const std::vector<Record> b = rollout();
    if (a.size() != b.size()) {
      problem("the same seed and actions gave episodes of different lengths");
      return;
    }
    for (size_t t = 0; t < a.size(); ++t) {
      const std::string where = " (record " + std::to_string(t) + ")";
      if (!identical(a[t].obs, b[t].obs)) {
        problem("the same seed and actions gave different observations: " + format(a[t].obs) +
                " vs " + format(b[t].obs) + where);
        return;
      }
      if (a[t].reward != b[t].reward || a[t].terminated != b[t].terminated ||
          a[t].truncated != b[t].truncated) {
        problem("the same seed and actions gave different rewards or flags" + where);
        return;
      }
      if (!identical_values(a[t].info, b[t].info)) {
        problem("the same seed and actions gave different info values" + where);
        return;
      }
    }
  }

  Env& env_;
  uint64_t seed_;
  int steps_;
  std::vector<std::string> problems_;
  std::string phase_ = "setup";  // what the env was doing, for exception reports
};

}  // namespace

std::vector<std::string> check_env(Env& env, uint64_t seed, int steps) {
  return Checker(env, seed, steps).run();
}

}  // namespace rlrun
