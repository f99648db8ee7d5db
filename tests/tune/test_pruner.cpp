// The pruners against Optuna 3.1's rules (optuna/pruners/_percentile.py, _successive_halving.py),
// on hand-made studies whose answers follow from those files.
#include <catch2/catch.hpp>

#include "rlrun/tune/pruner.hpp"

using namespace rlrun::tune;

namespace {

FrozenTrial trial(int number, TrialState state, std::map<int64_t, double> reports) {
  FrozenTrial t;
  t.trial_id = number;
  t.number = number;
  t.state = state;
  t.intermediate_values = std::move(reports);
  return t;
}

const SetSystemAttr kNoAttr = [](const std::string&, const nlohmann::json&) {};

}  // namespace

TEST_CASE("median pruner: Optuna's startup, warm-up, interval and median rules", "[tune]") {
  std::vector<FrozenTrial> trials;
  for (int i = 0; i < 5; ++i)  // completed trials: 1, 2, 3, 4, 5 at step 3
    trials.push_back(trial(i, TrialState::kComplete, {{1, 0.0}, {2, 0.0}, {3, i + 1.0}}));
  PrunerConfig config;  // median, 5 startup trials
  auto pruner = make_pruner(config, 0);
  const auto judge = [&](std::map<int64_t, double> reports, StudyDirection direction) {
    std::vector<FrozenTrial> all = trials;
    all.push_back(trial(5, TrialState::kRunning, std::move(reports)));
    return pruner->prune(StudyView{direction, all}, all.back(), kNoAttr);
  };
  // Maximise: the median at step 3 is 3; the trial's best so far decides.
  CHECK(judge({{3, 2.5}}, StudyDirection::kMaximize));
  CHECK_FALSE(judge({{3, 3.5}}, StudyDirection::kMaximize));
  CHECK_FALSE(judge({{1, 4.0}, {3, 2.5}}, StudyDirection::kMaximize));  // best over steps = 4
  // Minimise: prune above the median.
  CHECK(judge({{3, 3.5}}, StudyDirection::kMinimize));
  CHECK_FALSE(judge({{3, 2.5}}, StudyDirection::kMinimize));
  // A step no completed trial reported: nothing to compare with.
  CHECK_FALSE(judge({{4, -100.0}}, StudyDirection::kMaximize));
  // All NaN: pruned.
  CHECK(judge({{3, std::nan("")}}, StudyDirection::kMaximize));
  // Fewer completed trials than n_startup_trials: never.
  trials.pop_back();
  CHECK_FALSE(judge({{3, -100.0}}, StudyDirection::kMaximize));
  trials.push_back(trial(4, TrialState::kPruned, {{3, 5.0}}));  // pruned ones do not count
  CHECK_FALSE(judge({{3, -100.0}}, StudyDirection::kMaximize));
  trials.back().state = TrialState::kComplete;

  // Warm-up: no pruning before step n_warmup_steps (the default is the zoo's evaluations / 3).
  auto warm = make_pruner(config, 4);
  {
    std::vector<FrozenTrial> all = trials;
    all.push_back(trial(5, TrialState::kRunning, {{3, -100.0}}));
    CHECK_FALSE(warm->prune(StudyView{StudyDirection::kMaximize, all}, all.back(), kNoAttr));
  }
  // interval_steps 2 (warm-up 0): checks at steps 0, 2, 4 ...; step 3 is checked only when the
  // trial reported nothing since step 2.
  config.interval_steps = 2;
  auto interval = make_pruner(config, 0);
  for (auto [reports, expected] : std::vector<std::pair<std::map<int64_t, double>, bool>>{
           {{{3, -100.0}}, true},
           {{{2, -100.0}, {3, -100.0}}, false},
           {{{1, -100.0}, {3, -100.0}}, true}}) {
    std::vector<FrozenTrial> all = trials;
    all.push_back(trial(5, TrialState::kRunning, reports));
    CHECK(interval->prune(StudyView{StudyDirection::kMaximize, all}, all.back(), kNoAttr) ==
          expected);
  }
}

TEST_CASE("percentile pruner: numpy's interpolated percentile", "[tune]") {
  std::vector<FrozenTrial> trials;
  for (int i = 0; i < 5; ++i) trials.push_back(trial(i, TrialState::kComplete, {{1, i * 10.0}}));
  PrunerConfig config;
  config.type = "percentile";
  config.percentile = 25;  // maximise: keep the top 25 %: the 75th percentile of 0..40 is 30
  config.n_startup_trials = 0;
  auto pruner = make_pruner(config, 0);
  for (auto [value, expected] : std::vector<std::pair<double, bool>>{{29.9, true}, {30.0, false}}) {
    std::vector<FrozenTrial> all = trials;
    all.push_back(trial(5, TrialState::kRunning, {{1, value}}));
    CHECK(pruner->prune(StudyView{StudyDirection::kMaximize, all}, all.back(), kNoAttr) ==
          expected);
  }
}

TEST_CASE("successive halving: rungs, promotion of the top quarter, recorded rung values",
          "[tune]") {
  PrunerConfig config;
  config.type = "successive_halving";
  config.min_resource = 1;
  config.reduction_factor = 4;
  auto pruner = make_pruner(config, 0);
  std::vector<FrozenTrial> trials;
  for (int i = 0; i < 7; ++i) {  // earlier trials reached rung 0 with 1..7
    FrozenTrial t = trial(i, TrialState::kComplete, {{1, i + 1.0}});
    t.system_attrs["completed_rung_0"] = i + 1.0;
    trials.push_back(t);
  }
  const auto judge = [&](double value, StudyDirection direction,
                         std::vector<std::string>& written) {
    std::vector<FrozenTrial> all = trials;
    all.push_back(trial(7, TrialState::kRunning, {{1, value}}));
    return pruner->prune(
        StudyView{direction, all}, all.back(),
        [&](const std::string& key, const nlohmann::json&) { written.push_back(key); });
  };
  // 8 competitors, 8 // 4 - 1 = index 1: maximise needs >= the second largest of 1..7 and v
  // (the top quarter: 7 and 6.5 would both go on; 5.5 is below 6).
  std::vector<std::string> written;
  CHECK(judge(5.5, StudyDirection::kMaximize, written));
  CHECK(written == std::vector<std::string>{"completed_rung_0"});
  written.clear();
  CHECK_FALSE(judge(6.5, StudyDirection::kMaximize, written));
  // 7.5 >= 7: promoted to rung 1 (step 4), which step 1 has not reached: continue.
  CHECK_FALSE(judge(7.5, StudyDirection::kMaximize, written));
  // Minimise: <= the second smallest (1.5 of 1, 1.5, 2, ...).
  CHECK_FALSE(judge(1.5, StudyDirection::kMinimize, written));
  CHECK(judge(2.5, StudyDirection::kMinimize, written));
  // Before the first rung (min_resource 8): no judgement, nothing written.
  config.min_resource = 8;
  auto late = make_pruner(config, 0);
  std::vector<FrozenTrial> all = trials;
  all.push_back(trial(7, TrialState::kRunning, {{1, -100.0}}));
  written.clear();
  CHECK_FALSE(
      late->prune(StudyView{StudyDirection::kMaximize, all}, all.back(),
                  [&](const std::string& key, const nlohmann::json&) { written.push_back(key); }));
  CHECK(written.empty());
}

TEST_CASE("successive halving: min_resource auto waits for a completed trial", "[tune]") {
  PrunerConfig config;
  config.type = "successive_halving";
  auto pruner = make_pruner(config, 0);
  std::vector<FrozenTrial> all{trial(0, TrialState::kRunning, {{50, 1.0}})};
  CHECK_FALSE(pruner->prune(StudyView{StudyDirection::kMaximize, all}, all.back(), kNoAttr));
}
