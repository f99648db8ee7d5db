// Spaces without a simulator: an env's spaces come from its entry
// (EnvEntry::spaces) or from the model file (meta.json "env_spaces"), so parsing an experiment,
// `rlrun list`, `rlrun export` and rlrun::Policy::load start no Python worker, and the JSON
// form of spaces a model file holds is checked like any untrusted input.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "envs/python_env_runner.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/zip_archive.hpp"
#include "rlrun/core/zip_reader.hpp"
#include "rlrun/env/space_json.hpp"
#include "rlrun/policy.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/io/model_file.hpp"
#include "rlrun/runtime/io/model_policy.hpp"

using namespace rlrun;
using namespace rlrun::testing;
using nlohmann::json;

namespace {

const std::string kCartPolePort = "python:rlrun_test_envs.cartpole:CartPolePort";

// A Python interpreter that writes a line to `log` each time it starts, then runs Debian's.
std::string counting_python(const TempDir& dir) {
  const std::string path = dir / "counting_python";
  std::ofstream(path) << "#!/bin/sh\necho started >> '" << (dir / "starts.log") << "'\nexec "
                      << kPython << " \"$@\"\n";
  std::filesystem::permissions(path, std::filesystem::perms::owner_all);
  return path;
}

int python_starts(const TempDir& dir) {
  std::ifstream in(dir / "starts.log");
  int n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

std::string python_config(const TempDir& dir, const std::string& algo) {
  return write_file(dir / "py.yaml", "run: {name: py, seed: 1, total_timesteps: 256, out_dir: " +
                                         dir.str() + "/runs}\nenv: {id: \"" + kCartPolePort +
                                         "\", n_envs: 2, python: " + counting_python(dir) +
                                         "}\nalgo: {" + algo + "}\n");
}

// Every member of a model file, as written.
ZipMembers members_of(const std::string& model) {
  ZipReader reader(model);
  ZipMembers members;
  for (const ZipEntry& e : reader.entries()) members[e.name] = reader.read(e, uint64_t{1} << 26);
  return members;
}

Space round_trip(const Space& s) { return space_from_json(json::parse(space_to_json(s).dump())); }

}  // namespace

TEST_CASE("space JSON: every kind round-trips exactly", "[spaces]") {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const std::vector<Space> spaces = {
      Space::box({-4.8f, -kInf, -0.41887903f, 0.1f}, {4.8f, kInf, 0.41887903f, 1e30f}),
      Space::image({4, 84, 84}),
      Space::box(0.0f, 255.0f, {4, 84, 84}),  // float32 pixels stay float32
      Space::discrete(7, -3),
      Space::multi_discrete({3, 2, 5}),
      Space::multi_binary(6),
      Space::dict({{"goal", Space::box(-1.0f, 1.0f, {2})}, {"cell", Space::discrete(9)}}),
  };
  for (const Space& s : spaces) {
    INFO(s.describe());
    const Space back = round_trip(s);
    CHECK(back == s);
    CHECK(back.low() == s.low());
    CHECK(back.high() == s.high());
    CHECK(back.shape() == s.shape());
    CHECK(back.dtype() == s.dtype());
  }
  // A Python env's other numpy dtypes are float32 to rlrun; uint8 is kept.
  CHECK(space_from_json(
            json::parse(R"({"kind": "Box", "shape": [2], "low": 0, "high": 9, "dtype": "int64"})"))
            .dtype() == BoxDtype::kFloat32);
  CHECK(space_from_json(
            json::parse(R"({"kind": "Box", "shape": [2], "low": 0, "high": 9, "dtype": "uint8"})"))
            .is_uint8_box());
  // An image's bounds are one number each, not 28 224.
  CHECK(space_to_json(Space::image({4, 84, 84})).dump().size() < 100);
}

TEST_CASE("space JSON: malformed or oversized spaces are refused before anything is built",
          "[spaces]") {
  const std::vector<std::pair<std::string, std::string>> bad = {
      {R"([1, 2])", "JSON object"},
      {R"({"kind": "Tuple"})", "unknown space kind"},
      {R"({"kind": 3})", "not a string"},
      {R"({"kind": "Box", "shape": [2], "low": [0], "high": [1, 1]})", "low has 1 values"},
      {R"({"kind": "Box", "shape": [], "low": 0, "high": 1})", "1 to 8 sizes"},
      {R"({"kind": "Box", "shape": [-2], "low": 0, "high": 1})", "floats per sample"},
      {R"({"kind": "Box", "shape": [65536, 65536, 65536, 65536], "low": 0, "high": 1})",
       "more than 16777216"},
      {R"({"kind": "Box", "shape": [1.5], "low": 0, "high": 1})", "whole number"},
      {R"({"kind": "Box", "shape": [2], "low": 1, "high": 0})", "low > high"},
      {R"({"kind": "Box", "shape": [1], "low": "nan", "high": 0})", "bound is 'nan'"},
      {R"({"kind": "Box", "shape": [1], "low": null, "high": 0})", "bound is null"},
      {R"({"kind": "Discrete", "n": 0})", "positive"},
      {R"({"kind": "Discrete", "n": 18446744073709551615})", "too many values"},
      {R"({"kind": "Discrete", "n": 1e300})", "too many values"},
      {R"({"kind": "MultiBinary", "n": 2147483647})", "floats per sample"},
      {R"({"kind": "MultiDiscrete", "nvec": 4})", "list of at most"},
      {R"({"kind": "Dict", "spaces": {"a": {"kind": "Dict", "spaces": {}}}})", "inside a Dict"},
      {R"({"kind": "Dict", "spaces": []})", "JSON object"},
      {R"({"kind": "Box", "low": 0, "high": 1})", "no \"shape\""},
  };
  for (const auto& [text, why] : bad) {
    INFO(text);
    try {
      (void)space_from_json(json::parse(text));
      FAIL("accepted");
    } catch (const std::invalid_argument& e) {
      CHECK_THAT(e.what(), Catch::Contains(why));
    }
  }
}

TEST_CASE("every built-in env declares the spaces it has when built", "[spaces]") {
  const Registry& registry = builtin_registry();
  int checked = 0;
  for (const EnvEntry& entry : registry.envs()) {
    if (entry.expand) {
      CHECK(!entry.spaces);  // python:, gymnasium:: only the running worker knows
      continue;
    }
    INFO(entry.id);
    REQUIRE(entry.spaces);
    const AnyConfig kwargs = entry.parse(ConfigNode());
    const EnvSpaces declared = entry.spaces(kwargs);
    const EnvPtr built = entry.build(kwargs, EnvContext{});
    CHECK(declared.observation == built->observation_space());
    CHECK(declared.action == built->action_space());
    CHECK(declared.num_agents == built->num_agents());
    ++checked;
  }
  CHECK(checked >= 20);
}

TEST_CASE("parsing a Python env's experiment starts no worker, and the checks run once it is built",
          "[spaces][python]") {
  TempDir dir("spaces_parse_python");
  Registry registry = make_builtin_registry();
  const Experiment exp = load_experiment(python_config(dir, "id: PPO, n_steps: 64"), {}, registry);
  CHECK(exp.env.id == kCartPolePort);
  CHECK(python_starts(dir) == 0);

  // gSDE needs Box actions: unknown while parsing, refused by make_algorithm with the algo
  // section's position once the env's spaces are known.
  const std::string sde = python_config(dir, "id: PPO, n_steps: 64, use_sde: true");
  const Experiment with_sde = load_experiment(sde, {}, registry);
  try {
    (void)make_algorithm(with_sde, registry,
                         AlgorithmSetup{Space::box(-1.0f, 1.0f, {4}), Space::discrete(2), 2, 1});
    FAIL("gSDE with Discrete actions was accepted");
  } catch (const ConfigError& e) {
    CHECK_THAT(e.what(), Catch::Contains("py.yaml:3:") && Catch::Contains("algo.use_sde: gSDE"));
  }
  const auto r = run_rlrun_python("train " + sde);
  INFO(r.output);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("algo.use_sde: gSDE can only be used with continuous"));
}

TEST_CASE(
    "a Python env's model: export and rlrun::Policy::load start no Python, and act as "
    "eval does",
    "[spaces][python][deploy]") {
  TempDir dir("spaces_policy_python");
  const std::string config = python_config(dir, "id: PPO, n_steps: 64, batch_size: 64");
  auto r = run_rlrun_python("train " + config);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(python_starts(dir) == 2);  // one worker per env copy, none for parsing
  const std::string model = dir / "runs/py/seed1/model.zip";

  // The recorded spaces: the env's own.
  const ModelFile header = read_model_header(model);
  REQUIRE(header.meta.env_spaces);
  CHECK(header.meta.env_spaces->observation.is_box());
  CHECK(header.meta.env_spaces->observation.low()[0] == -4.8f);
  CHECK(header.meta.env_spaces->action == Space::discrete(2));

  // eval runs the env (the interpreter vouched for on the command line) and writes what the
  // policy saw and did.
  r = run_rlrun_python(
      "eval --model " + model + " --episodes 2 --deterministic --set env.id=" + kCartPolePort +
      " --set env.python=" + (dir / "counting_python") + " --trajectory " + (dir / "steps.csv"));
  REQUIRE(r.exit_code == 0);
  const int after_eval = python_starts(dir);
  CHECK(after_eval == 3);

  // No interpreter on PATH, no vouching: export and the deploy library need none.
  r = run_command("PATH=/nonexistent " + std::string(RLRUN_BINARY) + " export --model " + model +
                  " --format c --output " + (dir / "policy.c"));
  INFO(r.output);
  CHECK(r.exit_code == 0);
  const Policy policy = Policy::load(model);
  ModelPolicy from_python_package(model, builtin_registry());
  CHECK(python_starts(dir) == after_eval);

  // The trajectory's obs_i and action_0 columns (runtime/run/trajectory_tap.hpp): what the env
  // gave the policy and what the policy did.
  std::ifstream steps(dir / "steps.csv");
  std::string line;
  REQUIRE(std::getline(steps, line));
  std::vector<size_t> obs_columns;
  size_t action_column = 0;
  {
    std::stringstream header(line);
    size_t i = 0;
    for (std::string cell; std::getline(header, cell, ','); ++i) {
      if (cell.rfind("obs_", 0) == 0) obs_columns.push_back(i);
      if (cell == "action_0") action_column = i;
    }
  }
  REQUIRE(obs_columns.size() == 4);
  REQUIRE(action_column > 0);
  int compared = 0;
  while (std::getline(steps, line)) {
    std::vector<float> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');)
      cells.push_back(std::strtof(cell.c_str(), nullptr));
    std::vector<float> obs;
    for (size_t c : obs_columns) obs.push_back(cells.at(c));
    float action = -1;
    policy.act(obs, {&action, 1});
    CHECK(action == cells.at(action_column));
    Eigen::MatrixXf predicted;
    from_python_package.predict(Eigen::Map<const Eigen::MatrixXf>(obs.data(), 4, 1), true,
                                predicted);
    CHECK(predicted(0, 0) == cells.at(action_column));
    ++compared;
  }
  CHECK(compared > 10);

  // A program of the user's own, linked with the deploy library alone (which links no
  // simulator), acts with the model where no Python is installed.
  const std::string program = dir / "act.cpp";
  std::ofstream(program) << "#include <rlrun/policy.hpp>\n#include <cstdio>\n#include <vector>\n"
                            "int main(int, char** argv) {\n"
                            "  const rlrun::Policy p = rlrun::Policy::load(argv[1]);\n"
                            "  std::vector<float> obs = {0.01f, -0.2f, 0.03f, 0.4f}, act(1);\n"
                            "  p.act(obs, act);\n  std::printf(\"action %g\\n\", act[0]);\n}\n";
  const std::string library_dir = std::filesystem::path(RLRUN_POLICY_LIBRARY).parent_path();
  r = run_command(std::string(RLRUN_CXX_COMPILER) + " -std=c++20 -I" + kSourceDir + "/include " +
                  program + " -o " + (dir / "act") + " -L" + library_dir +
                  " -lrlrun_policy -Wl,-rpath," + library_dir);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  r = run_command("PATH=/nonexistent " + (dir / "act") + " " + model);
  INFO(r.output);
  CHECK(r.exit_code == 0);
  float expected = -1;
  const std::vector<float> obs = {0.01f, -0.2f, 0.03f, 0.4f};
  policy.act(obs, {&expected, 1});
  CHECK(r.output == "action " + std::to_string(static_cast<int>(expected)) + "\n");
  CHECK(python_starts(dir) == after_eval);
}

TEST_CASE("the deploy library links no simulator", "[spaces][deploy]") {
  const auto r = run_command(std::string("ldd ") + RLRUN_POLICY_LIBRARY);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  for (const char* simulator :
       {"sumo", "Bullet", "box2d", "pugixml", "python", "cairo", "tracicpp", "mujoco"})
    CHECK(r.output.find(simulator) == std::string::npos);
}

TEST_CASE("a model file without recorded spaces (older rlrun) still loads for predict and export",
          "[spaces][deploy]") {
  TempDir dir("spaces_old_model");
  const std::string config = write_file(
      dir / "cp.yaml", "run: {name: cp, seed: 1, total_timesteps: 512, out_dir: " + dir.str() +
                           "/runs}\nenv: {id: CartPole-v1}\n"
                           "algo: {id: PPO, n_steps: 128, batch_size: 64}\n");
  const auto r = run_rlrun("train " + config);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string model = dir / "runs/cp/seed1/model.zip";
  ZipMembers members = members_of(model);
  json meta = json::parse(members["meta.json"].begin(), members["meta.json"].end());
  meta.erase("env_spaces");
  const std::string text = meta.dump(2);
  members["meta.json"] = std::vector<uint8_t>(text.begin(), text.end());
  const std::string old = dir / "old.zip";
  write_zip_atomic(old, members);

  REQUIRE(!read_model_header(old).meta.env_spaces);
  // The Python package and export learn the spaces from the env's declaration.
  ModelPolicy now(model, builtin_registry()), before(old, builtin_registry());
  const std::vector<float> obs = {0.01f, -0.2f, 0.03f, 0.4f};
  Eigen::MatrixXf a, b;
  now.predict(Eigen::Map<const Eigen::MatrixXf>(obs.data(), 4, 1), true, a);
  before.predict(Eigen::Map<const Eigen::MatrixXf>(obs.data(), 4, 1), true, b);
  CHECK(a == b);
  const auto exported = run_rlrun("export --model " + old + " --format c --output " + (dir / "c"));
  INFO(exported.output);
  CHECK(exported.exit_code == 0);
  // The deploy library has no env to ask: it says so.
  CHECK(Policy::load(model).action_size() == 1);
  try {
    (void)Policy::load(old);
    FAIL("accepted");
  } catch (const std::runtime_error& e) {
    CHECK_THAT(e.what(), Catch::Contains("did not record the env's spaces"));
  }
}

TEST_CASE("a model file's env_spaces is untrusted: malformed ones are refused naming the file",
          "[spaces]") {
  TempDir dir("spaces_bad_meta");
  const std::string config = write_file(
      dir / "cp.yaml", "run: {name: cp, seed: 1, total_timesteps: 256, out_dir: " + dir.str() +
                           "/runs}\nenv: {id: CartPole-v1}\n"
                           "algo: {id: PPO, n_steps: 128, batch_size: 64}\n");
  REQUIRE(run_rlrun("train " + config).exit_code == 0);
  const std::string model = dir / "runs/cp/seed1/model.zip";
  ZipMembers members = members_of(model);
  const json good = json::parse(members["meta.json"].begin(), members["meta.json"].end());
  const std::vector<std::pair<json, std::string>> cases = {
      {json("Box"), "'env_spaces' is not a JSON object"},
      {json{{"action_space", good["env_spaces"]["action_space"]}, {"num_agents", 1}},
       "has no 'observation_space'"},
      {json{{"observation_space", {{"kind", "MultiBinary"}, {"n", 1 << 30}}},
            {"action_space", good["env_spaces"]["action_space"]},
            {"num_agents", 1}},
       "floats per sample"},
      {json{{"observation_space", good["env_spaces"]["observation_space"]},
            {"action_space", good["env_spaces"]["action_space"]},
            {"num_agents", 100000}},
       "num_agents is 100000"},
  };
  for (const auto& [env_spaces, why] : cases) {
    json meta = good;
    meta["env_spaces"] = env_spaces;
    const std::string text = meta.dump();
    members["meta.json"] = std::vector<uint8_t>(text.begin(), text.end());
    const std::string bad = dir / "bad.zip";
    write_zip_atomic(bad, members);
    INFO(why);
    try {
      (void)read_model_header(bad);
      FAIL("accepted");
    } catch (const RuntimeFailure& e) {
      CHECK_THAT(e.what(),
                 Catch::Contains(bad + ": meta.json is malformed") && Catch::Contains(why));
    }
  }
}
