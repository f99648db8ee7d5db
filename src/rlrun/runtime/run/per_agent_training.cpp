#include "rlrun/runtime/run/per_agent_training.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include <nlohmann/json.hpp>

#include "rlrun/core/dir_handle.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/plural.hpp"
#include "rlrun/core/thread_pool.hpp"
#include "rlrun/env/agent_names.hpp"
#include "rlrun/env/agent_seats.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/io/agent_team_file.hpp"
#include "rlrun/runtime/io/run_directory.hpp"
#include "rlrun/runtime/io/run_log.hpp"

namespace rlrun {

namespace {

// A directory name for an agent: its name with anything but letters, digits, '.', '_' and '-'
// made '_' (agent names come from the env: a traffic light's id may hold '#' or ':'), made
// distinct by the agent's index where two agents' names would meet.
std::vector<std::string> agent_directory_names(const std::vector<std::string>& agents) {
  std::vector<std::string> names;
  for (size_t a = 0; a < agents.size(); ++a) {
    std::string name;
    for (const char c : agents[a]) {
      const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                         (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '-';
      name += plain ? c : '_';
    }
    if (name.empty() || name.front() == '.' || name.front() == '-') name = "agent_" + name;
    // netconvert's joined junctions have ids of many OSM node ids ("cluster_1560223404_..."),
    // which can pass the 255 bytes a file name may have: cut, and made distinct by the index.
    constexpr size_t kLongest = 96;
    if (name.size() > kLongest) name = name.substr(0, kLongest - 16) + "_" + std::to_string(a);
    if (std::find(names.begin(), names.end(), name) != names.end()) name += "_" + std::to_string(a);
    names.push_back(std::move(name));
  }
  return names;
}

// What per-agent training cannot do yet, said at env.id before anything starts.
void check_per_agent_experiment(const Experiment& experiment) {
  const EnvSpec& spec = experiment.env;
  const auto refuse = [&](const std::string& what) {
    throw ConfigError(spec.where + ": env.agent_policies: per_agent does not support " + what +
                      " yet");
  };
  if (!spec.wrappers.empty()) refuse("env.wrappers");
  if (spec.section.normalize.enabled) refuse("env.normalize");
  if (spec.section.agent_indicator != "none")
    refuse("env.agent_indicator (each agent's policy is its own: no indicator is needed)");
  if (experiment.obs_log.freq > 0) refuse("obs_log");
  if (experiment.self_play.freq > 0) refuse("self_play");
}

// Agent `agent`'s copy of the experiment: its own run directory under the team's, its seed,
// and a quiet console for all but the first learner (k tables every few seconds would bury
// each other); the resolved config says the same.
Experiment learner_experiment(const Experiment& experiment, const std::string& team_dir,
                              const std::string& directory, int agent) {
  Experiment learner = experiment;
  learner.run.out_dir = team_dir + "/agents";
  learner.run.name = directory;
  learner.run.seed = experiment.run.seed + static_cast<uint64_t>(agent);
  if (agent > 0) learner.run.console_interval = 1e9;
  if (!experiment.run.tensorboard_log.value.empty())
    learner.run.tb_log_name =
        experiment.run.tb_log_name.value_or(experiment.run.name) + "_" + directory;
  learner.resolved = YAML::Clone(experiment.resolved);
  YAML::Node run = learner.resolved["run"];
  run["out_dir"] = learner.run.out_dir;
  run["name"] = learner.run.name;
  run["seed"] = learner.run.seed;
  run["console_interval"] = learner.run.console_interval;
  if (learner.run.tb_log_name) run["tb_log_name"] = *learner.run.tb_log_name;
  return learner;
}

struct LearnerResult {
  TrainOutcome outcome;
  std::exception_ptr failure;
  std::string error;
  int left_order = 0;  // 1 for the first learner to stop, ...
};

// Agent `agent`'s copy of `registry`: the env of `entry`'s id is the agent's seat at the next
// shared env of `table` (env/agent_seats.hpp).
Registry seat_registry(const Registry& registry, const EnvEntry& entry, SeatTable& table,
                       const std::function<EnvPtr()>& build_shared, int agent) {
  Registry learner = registry;
  EnvEntry seat = entry;
  seat.expand = nullptr;
  seat.independent_copies = false;  // seats meet at their shared env: never stepped at once
  seat.make = nullptr;
  seat.make_in_context = [&table, &build_shared, agent](const AnyConfig&,
                                                        const EnvContext&) -> EnvPtr {
    return std::make_unique<AgentSeat>(table.claim(agent, build_shared), agent);
  };
  learner.replace_env(std::move(seat));
  return learner;
}

// Runs learner a (experiments[a] with registries[a] on pools[a]) on a thread of its own, each
// leaving `table` when it stops; returns when all have stopped. `on_evaluation` hears
// learner 0.
std::vector<LearnerResult> run_learners(const std::vector<Experiment>& experiments,
                                        const std::vector<Registry>& registries,
                                        const std::vector<std::unique_ptr<ThreadPool>>& pools,
                                        SeatTable& table, const EvaluationListener& on_evaluation,
                                        const TrainOneLearner& train_one) {
  std::vector<LearnerResult> results(experiments.size());
  std::atomic<int> stopped{0};
  std::vector<std::thread> learners;
  for (size_t a = 0; a < experiments.size(); ++a) {
    learners.emplace_back([&, a] {
      LearnerResult& result = results[a];
      try {
        result.outcome = train_one(experiments[a], registries[a], ExecutionContext{pools[a].get()},
                                   a == 0 ? on_evaluation : EvaluationListener{});
      } catch (const std::exception& e) {
        result.failure = std::current_exception();
        result.error = e.what();
      }
      result.left_order = ++stopped;
      table.leave(static_cast<int>(a), result.error.empty() ? "finished" : result.error);
    });
  }
  for (std::thread& learner : learners) learner.join();
  return results;
}

// The team's outcome (the longest learner's steps and time) and agents.json's members from the
// learners' results; the failure of the first learner that failed, or null.
const LearnerResult* gather_team(const std::vector<LearnerResult>& results,
                                 const std::vector<std::string>& names, const std::string& team_dir,
                                 TrainOutcome& outcome, AgentTeam& team) {
  outcome.run_dir = team_dir;
  outcome.model_path = team_dir + "/" + kAgentTeamFile;
  const LearnerResult* first_failure = nullptr;
  for (size_t a = 0; a < results.size(); ++a) {
    const LearnerResult& r = results[a];
    if (r.failure && (!first_failure || r.left_order < first_failure->left_order))
      first_failure = &r;
    if (r.failure) continue;
    team.agents.push_back({names[a], r.outcome.run_dir.substr(team_dir.size() + 1)});
    outcome.timesteps = std::max(outcome.timesteps, r.outcome.timesteps);
    outcome.wall_seconds = std::max(outcome.wall_seconds, r.outcome.wall_seconds);
    outcome.interrupted = outcome.interrupted || r.outcome.interrupted;
    if (outcome.stop_reason.empty()) outcome.stop_reason = r.outcome.stop_reason;
  }
  return first_failure;
}

}  // namespace

TrainOutcome train_per_agent(const Experiment& experiment, const Registry& registry,
                             const ExecutionContext& execution, EvaluationListener on_evaluation,
                             const TrainOneLearner& train_one) {
  check_per_agent_experiment(experiment);
  const EnvSpec& spec = experiment.env;
  const EnvEntry* entry = registry.find_env(spec.id);
  if (!entry) throw ConfigError(spec.where + ": env.id: unknown environment '" + spec.id + "'");
  const AnyConfig kwargs = spec.kwargs.empty() ? entry->parse(ConfigNode()) : spec.kwargs;
  const EnvContext context = env_context(spec.section);
  // The first shared env, built now for its agents' names; the learners' first seats use it.
  EnvPtr first = entry->build(kwargs, context);
  const int agents = first->num_agents();
  if (agents < 2)
    throw ConfigError(spec.where +
                      ": env.agent_policies: per_agent trains one policy per agent "
                      "of a multi-agent env, and " +
                      spec.id + " has one agent");
  std::vector<std::string> names;
  for (int a = 0; a < agents; ++a) names.push_back(agent_name_of(*first, a));
  const std::vector<std::string> directories = agent_directory_names(names);

  const std::string team_dir =
      create_run_directory(experiment.run.out_dir, experiment.run.name, experiment.run.seed);
  const DirHandle dir = DirHandle::open(team_dir);
  dir.write_atomic("config.yaml", dump_yaml(experiment.resolved));
  RunLog log(team_dir + "/log.txt");
  const int threads_each = std::max(1, execution.threads() / agents);
  log.line("rlrun " RLRUN_VERSION ": training one " + experiment.algo.id +
           " learner per agent of " + spec.id + " (" + count_of(agents, "agent") + ", " +
           count_of(threads_each, "thread") + " each) for " +
           count_of(experiment.run.total_timesteps, "step") + " each (seed " +
           std::to_string(experiment.run.seed) + ") -> " + team_dir);

  SeatTable table(names);
  // The table builds shared envs one at a time (under its lock): `first` is handed out once.
  const std::function<EnvPtr()> build_shared = [&]() -> EnvPtr {
    if (first) return std::move(first);
    return entry->build(kwargs, context);
  };
  std::vector<Registry> registries;
  std::vector<Experiment> experiments;
  std::vector<std::unique_ptr<ThreadPool>> pools;
  for (int a = 0; a < agents; ++a) {
    registries.push_back(seat_registry(registry, *entry, table, build_shared, a));
    experiments.push_back(learner_experiment(experiment, team_dir, directories[a], a));
    pools.push_back(threads_each > 1 ? std::make_unique<ThreadPool>(threads_each) : nullptr);
  }

  const std::vector<LearnerResult> results =
      run_learners(experiments, registries, pools, table, on_evaluation, train_one);

  TrainOutcome outcome;
  AgentTeam team{spec.id, experiment.algo.id, {}};
  const LearnerResult* first_failure = gather_team(results, names, team_dir, outcome, team);
  if (first_failure) {
    log.line("a learner failed: " + first_failure->error);
    std::rethrow_exception(first_failure->failure);
  }
  dir.write_atomic(kAgentTeamFile, agent_team_json(team));
  log.line(format_session_summary(session_summary(outcome)) +
           "; the agents' models are listed in " + outcome.model_path + " (rlrun eval --model " +
           team_dir + ")");
  if (!outcome.interrupted)
    dir.write_atomic(kFinishedMarker, "timesteps " + std::to_string(outcome.timesteps) + "\n");
  return outcome;
}

}  // namespace rlrun
