#include "game_opponent_option.hpp"

#include <memory>

#include "rlrun/core/errors.hpp"
#include "rlrun/env/graph_policy.hpp"
#include "rlrun/env/policy_pool.hpp"
#include "rlrun/runtime/io/model_graph.hpp"
#include "rlrun/runtime/io/model_loader.hpp"

namespace rlrun::cli {

namespace {

constexpr const char* kModelPrefix = "model:";

}  // namespace

std::string GameOpponentOptions::opponent_model() const {
  return opponent.rfind(kModelPrefix, 0) == 0 ? opponent.substr(6) : "";
}

void add_game_opponent_options(CLI::App* sub, GameOpponentOptions& options) {
  sub->add_option("--opponent", options.opponent,
                  "two-player games (TicTacToe-v0, ConnectFour-v0): who plays the other side: "
                  "random, minimax (the env's minimax_depth), minimax:N (N plies) or model:FILE "
                  "(a model file or checkpoint, e.g. a past self)");
  sub->add_option("--side", options.side, "two-player games: the side the evaluated policy plays")
      ->check(CLI::IsMember({"first", "second", "alternate", "random"}));
}

void add_game_opponent_overrides(const GameOpponentOptions& options,
                                 std::vector<std::string>& overrides) {
  if (!options.side.empty()) overrides.push_back("env.kwargs.learner_side=" + options.side);
  const std::string& o = options.opponent;
  if (o.empty()) return;
  // The opponent as named: none of the training's epsilon-random moves.
  overrides.push_back("env.kwargs.opponent_random_moves=0");
  if (o == "random" || o == "minimax") {
    overrides.push_back("env.kwargs.opponent=" + o);
  } else if (o.rfind("minimax:", 0) == 0) {
    const std::string depth = o.substr(8);
    if (depth.empty() || depth.size() > 2 ||
        depth.find_first_not_of("0123456789") != std::string::npos)
      throw UsageError("--opponent " + o + ": minimax:N takes a depth of 1 to 42 plies");
    overrides.push_back("env.kwargs.opponent=minimax");
    overrides.push_back("env.kwargs.minimax_depth=" + depth);
  } else if (!options.opponent_model().empty()) {
    overrides.push_back("env.kwargs.opponent=self_play");
  } else {
    throw UsageError("--opponent " + o + ": random, minimax, minimax:N or model:FILE");
  }
}

void give_opponent_model(const GameOpponentOptions& options, Env& env, const Registry& registry) {
  const std::string path = options.opponent_model();
  if (path.empty()) return;
  auto* player = dynamic_cast<PlaysAgainstPool*>(&env.unwrapped());
  if (!player || !player->wants_policy_pool())
    throw UsageError("--opponent " + options.opponent + ": " + env.id() +
                     " is not a two-player game that plays a policy opponent");
  std::shared_ptr<const FrozenPolicy> policy;
  try {
    const LoadedModel opponent = load_model(path, registry, {}, {}, ModelEnv::kSpacesOnly);
    if (opponent.experiment.env.id != env.id())
      throw UsageError("--opponent " + options.opponent + ": the model plays " +
                       opponent.experiment.env.id + ", not " + env.id());
    policy = std::make_shared<GraphPolicy>(build_model_graph(opponent, /*with_value=*/false));
  } catch (const ExportError& e) {
    throw UsageError("--opponent " + options.opponent + ": " + e.what());
  }
  const auto* graph_policy = dynamic_cast<const GraphPolicy*>(policy.get());
  if (graph_policy->observation_width() != env.unwrapped().observation_space().flat_dim())
    throw UsageError("--opponent " + options.opponent +
                     ": the model does not read the game's own observation (a wrapper starts "
                     "its policy elsewhere)");
  auto pool = std::make_shared<PolicyPool>(1, 1.0);
  pool->add({0, 0, policy});
  player->set_policy_pool(pool);
}

}  // namespace rlrun::cli
