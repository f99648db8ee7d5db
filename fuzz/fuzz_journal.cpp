// Fuzz target: a study journal (Optuna's JournalFileStorage format, tune/journal_file.hpp) from
// arbitrary bytes, as `rlrun tune report` and a `rlrun tune` worker joining a shared study read
// it: the bytes become the journal file, which is read with the bounded line reader and replayed
// (tune/journal_replay.hpp, every field checked); then every study goes through what those
// commands do with it — the report (best trials, parameter importances by fANOVA), the TPE
// sampler (random start-up skipped, so the Parzen estimators see the fuzzed history) and the
// median and successive-halving pruners on each running trial.
// Refusing is fine (RuntimeFailure, UsageError, ConfigError: exit 1 or 2 naming the file and
// line); any other exception, a crash, a sanitizer report, a hang or a file descriptor left open
// (a long-lived worker would run out of them) is a bug. Every operation that reads back must
// also survive Python's json.dumps form (what rlrun appends) unchanged.
// Left out: the lock (a file-system protocol, not parsing) and plots (Cairo drawing of values
// the report already formats).
#include <fcntl.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "private_file.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/tune/journal_file.hpp"
#include "rlrun/tune/journal_storage.hpp"
#include "rlrun/tune/make_sampler.hpp"
#include "rlrun/tune/pruner.hpp"
#include "rlrun/tune/study_report.hpp"

using namespace rlrun;
using namespace rlrun::tune;

namespace {

// The lowest free file descriptor: the same before and after an input unless one leaked.
int lowest_free_descriptor() {
  const int fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  if (fd < 0) std::abort();  // descriptors exhausted: an earlier leak
  ::close(fd);
  return fd;
}

// What a worker's sampler does before a trial, on the study's history: the relative (joint)
// search space and a draw from it, then each parameter the history knows drawn on its own.
void sample_from(const StudyView& view) {
  SamplerConfig config;
  config.n_startup_trials = 0;  // straight to the Parzen estimators
  config.n_ei_candidates = 4;
  for (const bool multivariate : {true, false}) {
    config.multivariate = multivariate;
    const std::unique_ptr<Sampler> sampler = make_sampler(config);
    sampler->reseed(1, static_cast<int>(view.trials.size()));
    const SearchSpace space = sampler->infer_relative_search_space(view);
    sampler->sample_relative(view, space);
    std::map<std::string, Distribution> every;
    for (const FrozenTrial& t : view.trials)
      every.insert(t.distributions.begin(), t.distributions.end());
    for (const auto& [name, distribution] : every)
      sampler->sample_independent(view, name, distribution);
  }
}

// What a worker's pruner does after a running trial reports.
void prune_from(const StudyView& view) {
  PrunerConfig median;
  median.n_startup_trials = 0;
  PrunerConfig halving;
  halving.type = "successive_halving";
  for (const PrunerConfig& config : {median, halving}) {
    const std::unique_ptr<Pruner> pruner = make_pruner(config, 0);
    for (const FrozenTrial& t : view.trials) {
      if (t.state != TrialState::kRunning || t.intermediate_values.empty()) continue;
      pruner->prune(view, t, [](const std::string&, const nlohmann::json&) {});
    }
  }
}

void use_journal(const std::string& path) {
  JournalStorage storage(path, "fuzz-worker");
  const JournalReplay& state = storage.state();
  for (const std::string& name : state.study_names()) {
    const auto id = state.find_study(name);
    if (!id) std::abort();  // a listed study must be found by its name
    const StudyRecord& record = state.study(*id);
    if (record.directions.empty()) std::abort();  // replay refuses a study without one
    const StudyDirection direction = record.directions.front();
    const std::vector<FrozenTrial> trials = state.trials(*id);
    for (const FrozenTrial& t : trials) t.external_params();
    std::ostringstream report;
    ReportOptions options;
    options.top = 3;
    print_study_report(name, direction, trials, options, report);
    best_trial(trials, direction);
    const StudyView view{direction, trials};
    sample_from(view);
    prune_from(view);
  }
}

// Every operation read back as Python's json.dumps writes it, then read again: the same text.
void round_trip(const std::string& path) {
  JournalFile file(path);
  uint64_t lines = 0;
  for (const nlohmann::json& op : file.read(lines)) {
    const std::string text = python_json_text(op);
    if (python_json_text(parse_python_json(text, "again")) != text) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string& path = fuzz::private_file("journal", "study.log");
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) std::abort();
  }
  const int free_before = lowest_free_descriptor();
  try {
    round_trip(path);
    use_journal(path);
  } catch (const RuntimeFailure&) {
  } catch (const UsageError&) {
  } catch (const ConfigError&) {
  }
  if (lowest_free_descriptor() != free_before) std::abort();  // a descriptor leaked
  return 0;
}
