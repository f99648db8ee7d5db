// rlrun._core.Model: a model file loaded for prediction (runtime/io/model_policy.hpp: the env's
// own observations in, the env's own actions out, through the model's wrappers as `rlrun eval`
// steps them). python/rlrun/_model.py adds SB3's predict() signature and batching rules.
#include <pybind11/stl.h>

#include <algorithm>
#include <cstring>
#include <optional>

#include "bindings.hpp"
#include "rlrun/runtime/io/model_policy.hpp"

namespace rlrun::python {

namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// Returns the actions and, for a recurrent model given `state` (batch, state size) and
// `episode_start` (batch,), the next state in the same layout.
py::tuple predict(ModelPolicy& model, FloatArray obs, bool deterministic,
                  std::optional<FloatArray> action_masks, std::optional<FloatArray> state,
                  std::optional<FloatArray> episode_start) {
  // obs: (batch, obs_dim) C order = the bytes of an obs_dim x batch column-major matrix.
  const int obs_dim = model.observation_space().flat_dim();
  if (obs.ndim() != 2 || obs.shape(1) != obs_dim)
    throw py::value_error("predict: expected observations of shape (batch, " +
                          std::to_string(obs_dim) + ")");
  const Eigen::Index batch = obs.shape(0);
  const Eigen::Map<const Eigen::MatrixXf> in(obs.data(), obs_dim, batch);
  // action_masks: (batch, mask size) C order, as sb3-contrib's predict(action_masks=...).
  std::optional<Eigen::MatrixXf> masks;
  if (action_masks) {
    const int size = model.action_mask_size();
    if (size == 0)
      throw py::value_error("predict: action_masks given, but " + model.meta().algorithm +
                            " takes no action masks (MaskablePPO does)");
    if (action_masks->ndim() != 2 || action_masks->shape(1) != size ||
        action_masks->shape(0) != batch)
      throw py::value_error("predict: expected action_masks of shape (" + std::to_string(batch) +
                            ", " + std::to_string(size) + "), one mask per observation");
    masks = Eigen::Map<const Eigen::MatrixXf>(action_masks->data(), size, batch);
  }
  // state: (batch, state size) C order = a state size x batch column-major matrix.
  std::optional<Eigen::MatrixXf> states;
  Eigen::RowVectorXf starts;
  if (state) {
    const int size = model.recurrent_state_size();
    if (size == 0)
      throw py::value_error("predict: a state given, but " + model.meta().algorithm +
                            " has no recurrent state (RecurrentPPO does)");
    if (state->ndim() != 2 || state->shape(0) != batch || state->shape(1) != size)
      throw py::value_error("predict: expected a state of shape (" + std::to_string(batch) + ", " +
                            std::to_string(size) + ")");
    if (!episode_start || episode_start->size() != batch)
      throw py::value_error("predict: expected episode_start of shape (" + std::to_string(batch) +
                            ",)");
    states = Eigen::Map<const Eigen::MatrixXf>(state->data(), size, batch);
    starts = Eigen::Map<const Eigen::RowVectorXf>(episode_start->data(), batch);
  }
  Eigen::MatrixXf actions;
  {
    py::gil_scoped_release release;
    Eigen::MatrixXf no_states;
    const ModelPolicy::RecurrentInput recurrent{states ? *states : no_states, starts};
    model.predict(in, deterministic, actions, masks ? &*masks : nullptr,
                  states ? &recurrent : nullptr);
  }
  py::array_t<float> out(
      {static_cast<py::ssize_t>(batch), static_cast<py::ssize_t>(actions.rows())});
  std::copy(actions.data(), actions.data() + actions.size(), out.mutable_data());
  if (!states) return py::make_tuple(out, py::none());
  py::array_t<float> next(
      {static_cast<py::ssize_t>(batch), static_cast<py::ssize_t>(states->rows())});
  std::copy(states->data(), states->data() + states->size(), next.mutable_data());
  return py::make_tuple(out, next);
}

}  // namespace

namespace model_detail {

// A copy of a tensor as a numpy array of its dtype and shape.
py::array tensor_array(const Tensor& t) {
  py::dtype dtype = t.dtype == DType::kFloat32   ? py::dtype::of<float>()
                    : t.dtype == DType::kFloat64 ? py::dtype::of<double>()
                    : t.dtype == DType::kInt64   ? py::dtype::of<int64_t>()
                    : t.dtype == DType::kUInt64  ? py::dtype::of<uint64_t>()
                                                 : py::dtype::of<uint8_t>();
  py::array out(dtype, std::vector<py::ssize_t>(t.shape.begin(), t.shape.end()));
  std::memcpy(out.mutable_data(), t.bytes.data(), std::min<size_t>(t.bytes.size(), out.nbytes()));
  return out;
}

}  // namespace model_detail

void bind_model(py::module_& m) {
  using model_detail::tensor_array;
  py::class_<ModelPolicy>(m, "Model")
      .def(py::init(
               [](const std::string& path, const std::vector<std::string>& overrides, bool trust) {
                 // trust=True: runtime/io/model_trust.hpp, as the command line's --trust.
                 const ModelTrust accepted{trust, "trust=True"};
                 load_accepted_plugins(path, accepted, module_registry());
                 return std::make_unique<ModelPolicy>(path, module_registry(), overrides, accepted);
               }),
           py::arg("path"), py::arg("overrides") = std::vector<std::string>{},
           py::arg("trust") = false)
      .def("predict", &predict, py::arg("obs"), py::arg("deterministic"),
           py::arg("action_masks") = std::nullopt, py::arg("state") = std::nullopt,
           py::arg("episode_start") = std::nullopt)
      .def_property_readonly("recurrent_state_size", &ModelPolicy::recurrent_state_size)
      .def_property_readonly("recurrent_layers", &ModelPolicy::recurrent_layers)
      .def_property_readonly("action_mask_size", &ModelPolicy::action_mask_size)
      .def_property_readonly("algorithm",
                             [](const ModelPolicy& self) { return self.meta().algorithm; })
      .def_property_readonly("env_id", [](const ModelPolicy& self) { return self.meta().env_id; })
      .def_property_readonly("num_timesteps",
                             [](const ModelPolicy& self) { return self.meta().num_timesteps; })
      .def_property_readonly("rlrun_version",
                             [](const ModelPolicy& self) { return self.meta().rlrun_version; })
      .def_property_readonly("num_agents", &ModelPolicy::num_agents)
      .def_property_readonly(
          "observation_space",
          [](const ModelPolicy& self) { return space_dict(self.observation_space()); })
      .def_property_readonly(
          "action_space", [](const ModelPolicy& self) { return space_dict(self.action_space()); })
      .def_property_readonly(
          "policy_observation_space",
          [](const ModelPolicy& self) { return space_dict(self.policy_observation_space()); })
      .def_property_readonly(
          "policy_action_space",
          [](const ModelPolicy& self) { return space_dict(self.policy_action_space()); })
      .def_property_readonly("tensors",
                             [](const ModelPolicy& self) {
                               py::dict out;
                               for (const auto& [name, t] : self.tensors())
                                 out[py::str(name)] = tensor_array(t);
                               return out;
                             })
      .def_property_readonly("config_yaml", [](const ModelPolicy& self) {
        return dump_yaml(self.experiment().resolved);
      });
}

}  // namespace rlrun::python
