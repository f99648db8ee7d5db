// Python envs (python_env.hpp): two id families, expanded per id by the registry.
//   python:<module>:<Attr>   Attr(**env.kwargs), Attr a class or function of the module
//   gymnasium:<ID>           gymnasium.make(ID, **env.kwargs), with Gymnasium's own TimeLimit
//   pettingzoo:<module>:<fn> fn(**env.kwargs), a PettingZoo env: its agents share one policy
//                            (pettingzoo_agents.py)
//   python-object:<n>        a live env object of the `rlrun` Python package (python_live_env.hpp)
// env.kwargs is passed through as JSON (kwargs_json.hpp); env.python picks the interpreter.
#include <memory>
#include <regex>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/process_settings.hpp"
#include "rlrun/env/env_entry.hpp"
#include "rlrun/envs/python/kwargs_json.hpp"
#include "rlrun/envs/python/python_env.hpp"
#include "rlrun/envs/python/python_live_env.hpp"

namespace rlrun::envs {

namespace {

// env.python, where its default ("python3") gives way to RLRUN_PYTHON (ProcessSettings::python)
// when that is set: the `rlrun` Python package sets it to its own interpreter (sys.executable),
// so training from Python runs Python envs in the same interpreter, virtualenv and all.
std::string interpreter(const std::string& configured) {
  const std::string& preferred = process_settings().python;
  return configured == "python3" && !preferred.empty() ? preferred : configured;
}

EnvEntry python_entry(const std::string& id, std::string description) {
  EnvEntry entry;
  entry.id = id;
  entry.description = std::move(description);
  entry.runs_named_code = true;
  entry.parse = [](const ConfigNode& kwargs) {
    if (kwargs.defined() && !kwargs.is_map())
      kwargs.fail("the kwargs of a Python env are a map of its constructor's keyword arguments");
    try {
      (void)kwargs_json(kwargs.yaml());
    } catch (const std::invalid_argument& e) {
      kwargs.fail(std::string("cannot pass these kwargs to Python: ") + e.what());
    }
    YAML::Node copy =
        kwargs.defined() ? YAML::Clone(kwargs.yaml()) : YAML::Node(YAML::NodeType::Map);
    return AnyConfig::of_yaml(copy, copy);
  };
  entry.make_in_context = [id](const AnyConfig& kwargs, const EnvContext& context) -> EnvPtr {
    return std::make_unique<PythonEnv>(
        id, kwargs_json(kwargs.get<YAML::Node>()), interpreter(context.python),
        context.startup_timeout,
        PettingZooSettings{context.opponent, context.learner_side, context.agent_indicator});
  };
  entry.params = [] { return std::vector<FieldDoc>{}; };
  return entry;
}

// python:<module>:<Attr> and pettingzoo:<module>:<function>: `prefix` and the same form.
EnvEntry module_family(const std::string& prefix, const std::string& description,
                       const std::string& example, const std::string& kind) {
  EnvEntry family;
  family.id = prefix;
  family.description = description;
  family.params = [] { return std::vector<FieldDoc>{}; };
  family.expand = [prefix, example, kind](const std::string& id) {
    static const std::string name = "[A-Za-z_][A-Za-z0-9_]*(\\.[A-Za-z_][A-Za-z0-9_]*)*";
    const std::regex form(prefix + "(" + name + "):(" + name + ")");
    if (!std::regex_match(id, form))
      throw std::invalid_argument("'" + id + "' is not a " + kind + " id: write " + prefix +
                                  "<module>:<" + (prefix == "python:" ? "Class" : "function") +
                                  ">, e.g. " + example);
    return python_entry(id, kind + " " + id.substr(prefix.size()));
  };
  return family;
}

EnvEntry gymnasium_family() {
  EnvEntry family;
  family.id = "gymnasium:";
  family.description =
      "gymnasium:<ID>: gymnasium.make(ID, **kwargs) in a worker process (needs gymnasium in "
      "env.python's interpreter)";
  family.params = [] { return std::vector<FieldDoc>{}; };
  family.expand = [](const std::string& id) {
    static const std::regex form("gymnasium:[A-Za-z0-9_./:-]+");
    if (!std::regex_match(id, form))
      throw std::invalid_argument("'" + id +
                                  "' is not a Gymnasium env id: write "
                                  "gymnasium:<ID>, e.g. gymnasium:CartPole-v1");
    return python_entry(id, "gymnasium.make('" + id.substr(10) + "')");
  };
  return family;
}

// python-object:<n>: the connector's socket to the package's thread serving object n.
EnvEntry live_object_family() {
  EnvEntry family;
  family.id = "python-object:";
  family.description =
      "python-object:<n>: a gymnasium.Env object passed to rlrun.PPO(...) and the like from "
      "Python, stepped in that interpreter (only there)";
  family.params = [] { return std::vector<FieldDoc>{}; };
  family.expand = [](const std::string& id) {
    static const std::regex form("python-object:[0-9]{1,12}");
    if (!std::regex_match(id, form))
      throw std::invalid_argument("'" + id + "' is not a live env object's id (python-object:<n>)");
    EnvEntry entry = python_entry(id, "a live env object of the rlrun Python package");
    const int64_t number = std::stoll(id.substr(14));
    entry.make_in_context = [id, number](const AnyConfig& kwargs, const EnvContext& context) {
      const LiveEnvConnector& connect = live_env_connector();
      if (!connect)
        throw RuntimeFailure(id +
                             " names an env object that lives in a Python interpreter: it can be "
                             "built only there, by the rlrun package (rlrun.PPO(policy, env)); "
                             "name the env by its id (env.id) to use it here");
      auto worker = std::make_unique<PythonWorker>(PythonWorker::InProcess{}, connect(number),
                                                   interpreter(context.python));
      return std::make_unique<PythonEnv>(id, kwargs_json(kwargs.get<YAML::Node>()),
                                         std::move(worker), context.startup_timeout);
    };
    return entry;
  };
  return family;
}

}  // namespace

void register_python(EnvEntries& out) {
  out.push_back(module_family(
      "python:",
      "python:<module>:<Class>: a Gymnasium env written in Python, Class(**kwargs), one worker "
      "process per env (env.python: the interpreter)",
      "python:my_pkg.my_envs:MyEnv", "Python env"));
  out.push_back(gymnasium_family());
  out.push_back(module_family(
      "pettingzoo:",
      "pettingzoo:<module>:<function>: a PettingZoo env (parallel or AEC), function(**kwargs), "
      "its agents sharing one policy; turn-based games as one agent playing the seat to move",
      "pettingzoo:pettingzoo.classic.tictactoe_v3:env", "PettingZoo env"));
  out.push_back(live_object_family());
}

}  // namespace rlrun::envs
