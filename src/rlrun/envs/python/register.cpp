// Python envs (python_env.hpp): two id families, expanded per id by the registry.
//   python:<module>:<Attr>   Attr(**env.kwargs), Attr a class or function of the module
//   gymnasium:<ID>           gymnasium.make(ID, **env.kwargs), with Gymnasium's own TimeLimit
// env.kwargs is passed through as JSON (kwargs_json.hpp); env.python picks the interpreter.
#include <memory>
#include <regex>

#include "rlrun/core/process_settings.hpp"
#include "rlrun/env/env_entry.hpp"
#include "rlrun/envs/python/kwargs_json.hpp"
#include "rlrun/envs/python/python_env.hpp"

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
    return std::make_unique<PythonEnv>(id, kwargs_json(kwargs.get<YAML::Node>()),
                                       interpreter(context.python), context.startup_timeout);
  };
  entry.params = [] { return std::vector<FieldDoc>{}; };
  return entry;
}

EnvEntry python_family() {
  EnvEntry family;
  family.id = "python:";
  family.description =
      "python:<module>:<Class>: a Gymnasium env written in Python, Class(**kwargs), one worker "
      "process per env (env.python: the interpreter)";
  family.params = [] { return std::vector<FieldDoc>{}; };
  family.expand = [](const std::string& id) {
    static const std::regex form(
        "python:([A-Za-z_][A-Za-z0-9_]*(\\.[A-Za-z_][A-Za-z0-9_]*)*):"
        "([A-Za-z_][A-Za-z0-9_]*(\\.[A-Za-z_][A-Za-z0-9_]*)*)");
    if (!std::regex_match(id, form))
      throw std::invalid_argument("'" + id +
                                  "' is not a Python env id: write "
                                  "python:<module>:<Class>, e.g. python:my_pkg.my_envs:MyEnv");
    return python_entry(id, "Python env " + id.substr(7));
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

}  // namespace

void register_python(EnvEntries& out) {
  out.push_back(python_family());
  out.push_back(gymnasium_family());
}

}  // namespace rlrun::envs
