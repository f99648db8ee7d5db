#include "rlrun/runtime/io/model_graph.hpp"

#include <vector>

#include "rlrun/env/wrapper.hpp"

namespace rlrun {

PolicyGraph build_model_graph(const LoadedModel& model, bool with_value) {
  if (model.env->num_agents() != 1)
    throw ExportError("a multi-agent env (" + std::to_string(model.env->num_agents()) +
                      " agents) cannot be exported yet");
  // The wrapper stack, outermost first, down to the env itself.
  std::vector<const Wrapper*> stack;
  const Env* env = model.env.get();
  while (const auto* wrapper = dynamic_cast<const Wrapper*>(env)) {
    stack.push_back(wrapper);
    env = &wrapper->inner();
  }
  const Space& observation_space = env->observation_space();

  PolicyGraph graph;
  std::string obs;
  if (observation_space.kind() == SpaceKind::kDict) {
    std::vector<std::string> parts;
    for (size_t i = 0; i < observation_space.keys().size(); ++i) {
      const std::string& key = observation_space.keys()[i];
      graph.add_input(key, observation_space.subspaces()[i].flat_dim());
      parts.push_back(key);
    }
    obs = graph.concat(parts);
  } else {
    graph.add_input("obs", observation_space.flat_dim());
    obs = "obs";
  }
  // Up the stack: the innermost wrapper sees the env's observation first.
  for (auto it = stack.rbegin(); it != stack.rend(); ++it)
    obs = (*it)->export_observation(graph, obs);
  model.algorithm->export_policy(graph, obs, with_value);
  // Down the stack: the outermost wrapper receives the agent's action first.
  std::string action = graph.action();
  for (const Wrapper* wrapper : stack) action = wrapper->export_action(graph, action);
  graph.set_action(action);

  const ModelMeta& meta = model.file.meta;
  graph.metadata["env_id"] = meta.env_id;
  graph.metadata["algorithm"] = meta.algorithm;
  graph.metadata["rlrun_version"] = RLRUN_VERSION;
  graph.metadata["model_rlrun_version"] = meta.rlrun_version;
  graph.metadata["observation_space"] = meta.observation_space;
  graph.metadata["action_space"] = meta.action_space;
  graph.metadata["num_timesteps"] = std::to_string(meta.num_timesteps);
  graph.metadata["deterministic"] = "true";
  return graph;
}

}  // namespace rlrun
