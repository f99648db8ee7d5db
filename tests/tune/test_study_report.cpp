// `rlrun tune report`'s text and history plot (src/rlrun/tune/study_report.hpp).
#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>
#include <sstream>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/private_temp_dir.hpp"
#include "rlrun/tune/study_report.hpp"
#include "tune/synthetic_study.hpp"

using rlrun::tune::FrozenTrial;
using rlrun::tune::ReportOptions;
using rlrun::tune::StudyDirection;
using rlrun::tune::TrialState;
namespace synthetic = rlrun::tune::testing;

namespace {

// A maximised study: 30 trials of y = x1 + 0.3 x2, then a pruned, a failed and a running one.
std::vector<FrozenTrial> mixed_study() {
  std::vector<FrozenTrial> trials = synthetic::synthetic_study(synthetic::x1_then_x2, 30);
  trials[4].user_attrs["eval_seeds"] = {1, 2};
  for (TrialState state : {TrialState::kPruned, TrialState::kFail, TrialState::kRunning}) {
    FrozenTrial t = trials[0];
    t.number = static_cast<int>(trials.size());
    t.trial_id = t.number;
    t.state = state;
    t.values.reset();
    t.intermediate_values = {{1, 0.2}, {2, 0.4}};
    trials.push_back(t);
  }
  return trials;
}

std::string file_head(const std::string& path, size_t n) {
  std::ifstream in(path, std::ios::binary);
  std::string head(n, '\0');
  in.read(head.data(), static_cast<std::streamsize>(n));
  return head.substr(0, static_cast<size_t>(in.gcount()));
}

int best_number(const std::vector<FrozenTrial>& trials) {
  int best = -1;
  for (const FrozenTrial& t : trials)
    if (t.state == TrialState::kComplete &&
        (best < 0 || *t.value() > *trials[static_cast<size_t>(best)].value()))
      best = t.number;
  return best;
}

}  // namespace

TEST_CASE("The study report names the best trial and counts trials by state", "[tune]") {
  const auto trials = mixed_study();
  rlrun::PrivateTempDir dir("rlrun_test_tune_report_");
  ReportOptions options;
  options.top = 5;
  options.plot_path = dir.file("history.png");
  std::ostringstream out;
  print_study_report("ppo_cartpole", StudyDirection::kMaximize, trials, options, out);
  const std::string text = out.str();
  INFO(text);
  CHECK(text.find("study ppo_cartpole (maximize)") != std::string::npos);
  CHECK(text.find("33 trials: COMPLETE 30, PRUNED 1, FAIL 1, RUNNING 1, WAITING 0") !=
        std::string::npos);
  const int best = best_number(trials);
  const FrozenTrial& b = trials[static_cast<size_t>(best)];
  CHECK(text.find("best trial: " + std::to_string(best) + ", value ") != std::string::npos);
  // Its parameters as key=value, in shortest text (nlohmann's dump, as Python's repr).
  CHECK(text.find("x1=" + nlohmann::json(b.params.at("x1")).dump()) != std::string::npos);
  CHECK(text.find("top 5 of 30 complete trials:") != std::string::npos);
  // The top table's first row is the best trial.
  const size_t table = text.find("top 5 of");
  const size_t first_row = text.find('\n', text.find("params", table)) + 1;
  std::istringstream row(text.substr(first_row, text.find('\n', first_row) - first_row));
  int number = -1;
  row >> number;
  CHECK(number == best);
  // Importances: x1 first, with its bar.
  const size_t importances = text.find("parameter importances");
  REQUIRE(importances != std::string::npos);
  CHECK(text.find("  x1  ", importances) < text.find("  x2  ", importances));
  CHECK(text.find("####", importances) != std::string::npos);
  CHECK(text.find("history plot: " + options.plot_path) != std::string::npos);
  CHECK(file_head(options.plot_path, 8) == "\x89PNG\r\n\x1a\n");
}

TEST_CASE("The study report shows the best trial's user attrs and wraps long parameter lists",
          "[tune]") {
  std::vector<FrozenTrial> trials = synthetic::synthetic_study(synthetic::x1_only, 3);
  for (FrozenTrial& t : trials)
    for (int i = 0; i < 12; ++i) {
      const std::string name = "a_rather_long_parameter_name_" + std::to_string(i);
      t.distributions[name] = rlrun::tune::CategoricalDistribution{{"tanh", "relu"}};
      t.params[name] = 1;
    }
  trials[1].values = std::vector<double>{-5.0};  // the best when minimising
  trials[1].user_attrs["note"] = "lowest";
  std::ostringstream out;
  print_study_report("wide", StudyDirection::kMinimize, trials, {}, out);
  const std::string text = out.str();
  INFO(text);
  CHECK(text.find("best trial: 1, value -5.0") != std::string::npos);
  CHECK(text.find("user attrs: note=\"lowest\"") != std::string::npos);
  CHECK(text.find("a_rather_long_parameter_name_0=relu") != std::string::npos);
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) CHECK(line.size() <= 100);
}

TEST_CASE("The study report of a study without complete trials says so", "[tune]") {
  std::vector<FrozenTrial> trials = mixed_study();
  trials.erase(trials.begin(), trials.begin() + 30);
  rlrun::PrivateTempDir dir("rlrun_test_tune_report_");
  ReportOptions options;
  options.plot_path = dir.file("history.svg");
  std::ostringstream out;
  print_study_report("empty", StudyDirection::kMinimize, trials, options, out);
  const std::string text = out.str();
  INFO(text);
  CHECK(text.find("best trial: none") != std::string::npos);
  CHECK(text.find("top ") == std::string::npos);
  CHECK(text.find("  none: ") != std::string::npos);
  CHECK(text.find("(empty: no complete trial)") != std::string::npos);
  CHECK(file_head(options.plot_path, 5) == "<?xml");
}

TEST_CASE("The history plot is a PNG or an SVG by its extension", "[tune]") {
  const auto trials = mixed_study();
  rlrun::PrivateTempDir dir("rlrun_test_tune_report_");
  write_history_plot("study", StudyDirection::kMaximize, trials, dir.file("a.png"));
  CHECK(file_head(dir.file("a.png"), 8) == "\x89PNG\r\n\x1a\n");
  write_history_plot("study", StudyDirection::kMinimize, trials, dir.file("b.svg"), true);
  const std::string svg = file_head(dir.file("b.svg"), 1 << 20);
  CHECK(svg.rfind("<?xml", 0) == 0);
  CHECK(svg.find("<svg") != std::string::npos);
  CHECK_THROWS_AS(write_history_plot("study", StudyDirection::kMaximize, trials, dir.file("c.jpg")),
                  rlrun::UsageError);
  CHECK_THROWS_AS(
      write_history_plot("study", StudyDirection::kMaximize, trials, dir.path() + "/missing/d.png"),
      rlrun::RuntimeFailure);
}
