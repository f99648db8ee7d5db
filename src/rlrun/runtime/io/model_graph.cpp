#include "rlrun/runtime/io/model_graph.hpp"

#include <vector>

#include "rlrun/env/wrapper.hpp"

namespace rlrun {

namespace {

// The graph's observation inputs for `space`: one per Dict key (in the space's order, then
// concatenated), else one named "obs". Returns the observation's tensor.
std::string add_observation_inputs(PolicyGraph& graph, const Space& space) {
  if (space.kind() != SpaceKind::kDict) {
    graph.add_input("obs", space.flat_dim());
    return "obs";
  }
  std::vector<std::string> parts;
  for (size_t i = 0; i < space.keys().size(); ++i) {
    graph.add_input(space.keys()[i], space.subspaces()[i].flat_dim());
    parts.push_back(space.keys()[i]);
  }
  return graph.concat(parts);
}

}  // namespace

PolicyGraph build_model_graph(const LoadedModel& model, bool with_value) {
  if (model.env->num_agents() != 1)
    throw ExportError("a multi-agent env (" + std::to_string(model.env->num_agents()) +
                      " agents) cannot be exported yet");
  // The wrapper stack, innermost first, from the env itself.
  std::vector<const Wrapper*> stack;
  const Env* env = model.env.get();
  while (const auto* wrapper = dynamic_cast<const Wrapper*>(env)) {
    stack.insert(stack.begin(), wrapper);
    env = &wrapper->inner();
  }
  // Up the stack: the innermost wrapper sees the env's observation first. A wrapper whose
  // observation no graph can compute but which leaves actions alone (it renders the env or
  // keeps frames: AddRenderObservation, FrameStack, MaxAndSkip) moves the graph's input up to
  // its own observation — what the policy network reads, as SB3's exported policies read
  // preprocessed observations; the graph is rebuilt from there.
  size_t below = 0;  // wrappers under the graph's input
  PolicyGraph graph;
  std::string obs;
  for (bool built = false; !built;) {
    graph = PolicyGraph();
    obs = add_observation_inputs(
        graph, below == 0 ? env->observation_space() : stack[below - 1]->observation_space());
    built = true;
    for (size_t k = below; k < stack.size() && built; ++k) {
      try {
        obs = stack[k]->export_observation(graph, obs);
      } catch (const ExportError&) {
        if (!stack[k]->exports_action_unchanged()) throw;
        below = k + 1;
        built = false;
      }
    }
  }
  if (below > 0)
    graph.metadata["observation_input"] = "the observations of the wrapper " +
                                          wrapper_class_name(*stack[below - 1]) +
                                          " (the graph does not compute it nor what is under it)";
  model.algorithm->export_policy(graph, obs, with_value);
  // Down the stack: the outermost wrapper receives the agent's action first.
  std::string action = graph.action();
  for (auto it = stack.rbegin(); it != stack.rend(); ++it)
    action = (*it)->export_action(graph, action);
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
  if (graph.state_width() > 0)
    graph.metadata["recurrent_state"] =
        std::to_string(graph.state_width()) +
        " floats: the LSTM's h of every layer, then its c (the critic's LSTM's after the "
        "actor's when the value is exported); feed state_out back as state_in, zeros at the "
        "start of every episode";
  return graph;
}

}  // namespace rlrun
