// rlrun::Policy (include/rlrun/policy.hpp): the model's PolicyGraph (runtime/io/model_graph.hpp),
// compiled once into a list of steps over one scratch buffer per thread, so that act() is a
// few matrix-vector products and loops with no allocation and no shared mutable state.
#include "rlrun/policy.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "rlrun/nn/policy_graph.hpp"
#include "rlrun/runtime/components/policy_components.hpp"
#include "rlrun/runtime/io/model_graph.hpp"
#include "rlrun/runtime/io/model_loader.hpp"

namespace rlrun {

namespace {

// Where a tensor lives: a run of rows of the caller's observations (a graph input), the
// caller's states (a recurrent graph's state input), or its own width x batch block of the
// scratch buffer.
struct Slot {
  enum class Buffer { kObservation, kState, kScratch };
  Buffer buffer = Buffer::kScratch;
  int row = 0;  // observation: first row; scratch: first float per column (x batch)
  int width = 0;
};

}  // namespace

struct Policy::Impl {
  std::string env_id, algorithm;
  int observation_size = 0, action_size = 0, state_size = 0;
  PolicyGraph graph;
  std::vector<std::vector<Slot>> node_inputs;  // per node, resolved once
  std::vector<Slot> node_outputs;
  int scratch_rows = 0;  // floats per observation in the scratch buffer
  Slot action, next_state;

  void compile() {
    std::map<std::string, Slot> slots;  // tensor name -> where it lives
    for (const GraphInput& in : graph.inputs()) {
      slots[in.name] = {Slot::Buffer::kObservation, observation_size, in.width};
      observation_size += in.width;
    }
    state_size = graph.state_width();
    if (state_size > 0)
      slots[PolicyGraph::kStateInput] = {Slot::Buffer::kState, 0, graph.state_width()};
    for (const GraphNode& n : graph.nodes()) {  // in order: a node reads only earlier tensors
      std::vector<Slot> inputs;
      for (const std::string& in : n.inputs) inputs.push_back(slots.at(in));
      node_inputs.push_back(std::move(inputs));
      slots[n.output] = {Slot::Buffer::kScratch, scratch_rows, n.width};
      node_outputs.push_back(slots[n.output]);
      scratch_rows += n.width;
    }
    action = slots.at(graph.action());
    action_size = action.width;
    if (state_size > 0) next_state = slots.at(graph.state_output());
  }

  ConstGraphBlock view(const Slot& s, const float* obs, const float* states, const float* scratch,
                       Eigen::Index n) const {
    switch (s.buffer) {
      case Slot::Buffer::kObservation:
        return {obs + s.row, s.width, n, Eigen::OuterStride<>(observation_size)};
      case Slot::Buffer::kState: return {states, s.width, n, Eigen::OuterStride<>(state_size)};
      case Slot::Buffer::kScratch: break;
    }
    return {scratch + static_cast<Eigen::Index>(s.row) * n, s.width, n,
            Eigen::OuterStride<>(s.width)};
  }

  // `states`: the recurrent states in, the next ones out (null for a feed-forward graph).
  void run(const float* obs, float* states, float* actions, Eigen::Index n) const {
    thread_local std::vector<float> scratch;
    thread_local std::vector<ConstGraphBlock> inputs;  // reused: no allocation once grown
    const size_t needed = static_cast<size_t>(scratch_rows) * static_cast<size_t>(n);
    if (scratch.size() < needed) scratch.resize(needed);
    for (size_t i = 0; i < graph.nodes().size(); ++i) {
      const Slot& out = node_outputs[i];
      inputs.clear();
      for (const Slot& in : node_inputs[i])
        inputs.push_back(view(in, obs, states, scratch.data(), n));
      run_node(graph.nodes()[i], inputs,
               GraphBlock(scratch.data() + static_cast<Eigen::Index>(out.row) * n, out.width, n,
                          Eigen::OuterStride<>(out.width)));
    }
    Eigen::Map<Eigen::MatrixXf>(actions, action_size, n) =
        view(action, obs, states, scratch.data(), n);
    // Every node has read the old states by now.
    if (state_size > 0)
      Eigen::Map<Eigen::MatrixXf>(states, state_size, n) =
          view(next_state, obs, states, scratch.data(), n);
  }
};

Policy::Policy(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Policy::Policy(Policy&&) noexcept = default;
Policy& Policy::operator=(Policy&&) noexcept = default;
Policy::~Policy() = default;

Policy Policy::load(const std::string& model_path) {
  auto impl = std::make_unique<Impl>();
  try {
    // The model's env is never built: its spaces come from the file, so the registry holds
    // the wrappers and algorithms alone and this library links no env or simulator.
    const LoadedModel model =
        load_model(model_path, policy_registry(), {}, {}, ModelEnv::kSpacesOnly);
    impl->graph = build_model_graph(model, /*with_value=*/false);
    impl->env_id = model.file.meta.env_id;
    impl->algorithm = model.file.meta.algorithm;
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string("rlrun::Policy::load: ") + e.what());
  } catch (const std::exception& e) {
    throw std::runtime_error("rlrun::Policy::load: " + model_path + ": " + e.what());
  }
  impl->compile();
  return Policy(std::move(impl));
}

std::size_t Policy::observation_size() const {
  return static_cast<std::size_t>(impl_->observation_size);
}
std::size_t Policy::action_size() const { return static_cast<std::size_t>(impl_->action_size); }
std::size_t Policy::state_size() const { return static_cast<std::size_t>(impl_->state_size); }
const std::string& Policy::env_id() const { return impl_->env_id; }
const std::string& Policy::algorithm() const { return impl_->algorithm; }

void Policy::act(std::span<const float> observation, std::span<float> action) const {
  act_batch(observation, action, 1);
}

void Policy::act(std::span<const float> observation, std::span<float> state,
                 std::span<float> action) const {
  act_batch(observation, state, action, 1);
}

void Policy::act_batch(std::span<const float> observations, std::span<float> actions,
                       std::size_t count) const {
  if (state_size() > 0)
    throw std::invalid_argument("rlrun::Policy::act: this policy is recurrent (" +
                                std::to_string(state_size()) +
                                " floats of state): pass its state, act(observation, state, "
                                "action)");
  act_batch(observations, {}, actions, count);
}

void Policy::act_batch(std::span<const float> observations, std::span<float> states,
                       std::span<float> actions, std::size_t count) const {
  if (observations.size() != count * observation_size() ||
      actions.size() != count * action_size() || states.size() != count * state_size())
    throw std::invalid_argument(
        "rlrun::Policy::act: " + std::to_string(count) + " observation(s) of " +
        std::to_string(observation_size()) + " floats, " + std::to_string(state_size()) +
        " state floats and " + std::to_string(action_size()) +
        " action floats each expected, got " + std::to_string(observations.size()) + ", " +
        std::to_string(states.size()) + " and " + std::to_string(actions.size()));
  if (count == 0) return;
  impl_->run(observations.data(), states.data(), actions.data(), static_cast<Eigen::Index>(count));
}

}  // namespace rlrun
