// YAML merge keys (`<<: *defaults`, yaml.org/type/merge.html) in every config rlrun loads, as
// PyYAML reads them (rl-zoo's hyperparameter files use them for their MuJoCo and PyBullet
// sections): keys written in the map win, of several merged maps the earlier one.
#include <catch2/catch.hpp>

#include <string>

#include "rlrun/core/config_node.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"

using namespace rlrun;

namespace {

std::string load_error(const std::string& text) {
  try {
    ConfigNode::load_string(text, "m.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("config: YAML merge keys merge maps, written keys win", "[core][config][merge]") {
  const ConfigNode root = ConfigNode::load_string(R"(defaults: &defaults
  n_timesteps: 1000
  gamma: 0.9
  kwargs: {a: 1}
other: &other {gamma: 0.5, lam: 0.8, extra: 7}
one:
  <<: *defaults
  gamma: 0.99
two:
  <<: [*defaults, *other]
  lam: 0.95
nested: &nested
  <<: *defaults
  n_timesteps: 5
three: {<<: *nested, tag: x}
quoted: {"<<": 1}
)",
                                                  "m.yaml");
  const ConfigNode one = root.child("one");
  CHECK_FALSE(one.has("<<"));
  CHECK(one.child("gamma").as_double() == 0.99);     // written in the map
  CHECK(one.child("n_timesteps").as_int() == 1000);  // merged
  CHECK(one.child("kwargs").child("a").as_int() == 1);
  // A merged value keeps its own position (the anchor's lines).
  CHECK_THAT(one.child("n_timesteps").where(), Catch::Equals("m.yaml:2:16"));
  const ConfigNode two = root.child("two");
  CHECK(two.child("gamma").as_double() == 0.9);  // the earlier map wins
  CHECK(two.child("lam").as_double() == 0.95);
  CHECK(two.child("extra").as_int() == 7);
  // A merged map that merges itself: resolved first.
  CHECK(root.child("three").child("n_timesteps").as_int() == 5);
  CHECK(root.child("three").child("gamma").as_double() == 0.9);
  CHECK(root.child("three").keys().size() == 4);
  // A quoted "<<" is an ordinary key (as in PyYAML).
  CHECK(root.child("quoted").child("<<").as_int() == 1);
  // Merging adds no key twice and no `<<`.
  CHECK(one.keys().size() == 3);
}

TEST_CASE("config: a merge key names maps, else the error names its line",
          "[core][config][merge]") {
  CHECK_THAT(load_error("a: 1\nb:\n  <<: 5\n"),
             Catch::Contains("m.yaml:3:3") && Catch::Contains("a merge key (<<) takes a map"));
  CHECK_THAT(load_error("a: &a {x: 1}\nb: {<<: [*a, 2]}\n"), Catch::Contains("m.yaml:2:5"));
  CHECK_THAT(load_error("a: {x: 1}\nb: {<<: {y: 1}, <<: {z: 2}}\n"), Catch::Contains("repeats"));
}

TEST_CASE("config: an experiment file may use merge keys", "[core][config][merge]") {
  Registry registry = make_builtin_registry();
  const Experiment e = load_experiment_text(R"(run: {name: merged}
env: {id: CartPole-v1}
algo:
  <<: &common {gamma: 0.98, n_steps: 64, batch_size: 64}
  id: PPO
  n_steps: 128
)",
                                            "merged.yaml", "merged", {}, registry);
  CHECK(e.algo.params.resolved()["gamma"].as<double>() == 0.98);
  CHECK(e.algo.params.resolved()["n_steps"].as<int>() == 128);
}

// A collection that holds itself through an alias is endless when expanded: refused at once, at
// the collection, rather than after 100 000 expansions (fuzz_zoo, 2026-11-29: a 247-byte zoo
// file whose `default` map merged itself took 0.3 s to refuse, 3 s under ASan). Aliases used
// many times over (a DAG, as every zoo file's `<<: *defaults`) stay fine.
TEST_CASE("config: a recursive alias is refused at once with its position",
          "[core][config][merge]") {
  CHECK_THAT(load_error("default: &d\n  n_timesteps: 1000\n  bAcrobot-v0:\n  <<: *d\n"),
             Catch::Contains("m.yaml:1:10") && Catch::Contains("contains itself through an alias"));
  CHECK_THAT(load_error("a: &x\n  b: 1\n  c: *x\n"),
             Catch::Contains("contains itself through an alias"));
  CHECK_THAT(load_error("a: &x [1, [2, *x]]\n"),
             Catch::Contains("m.yaml:1:4") && Catch::Contains("contains itself"));
  CHECK_THAT(load_error("a: &x {b: [{c: *x}]}\n"), Catch::Contains("contains itself"));
  const ConfigNode shared = ConfigNode::load_string(
      "d: &d {x: 1, y: [1, 2]}\na: *d\nb: [*d, *d]\nc: {<<: *d, z: 3}\ne: {f: *d, g: *d}\n",
      "m.yaml");
  CHECK(shared.child("c").child("x").as_int() == 1);
  CHECK(shared.child("e").child("g").child("y").at(1).as_int() == 2);
}
