// env.kwargs of a Python env as the JSON its constructor receives (envs/python/kwargs_json.hpp):
// YAML 1.2 core-schema types, as yaml.safe_load would give them to a Python user.
#include <catch2/catch.hpp>

#include "rlrun/envs/python/kwargs_json.hpp"

using rlrun::kwargs_json;

TEST_CASE("Python env kwargs become JSON with YAML's scalar types", "[python]") {
  const YAML::Node kwargs = YAML::Load(
      "{size: 7, rate: 0.5, big: 1e3, name: grid, quoted: '12', flag: true, off: False, "
      "none: ~, list: [1, two, 3.5], nested: {a: null}}");
  CHECK(kwargs_json(kwargs) ==
        R"({"big":1000.0,"flag":true,"list":[1,"two",3.5],"name":"grid","nested":{"a":null},)"
        R"("none":null,"off":false,"quoted":"12","rate":0.5,"size":7})");
  CHECK(kwargs_json(YAML::Node()) == "{}");
  CHECK_THROWS_WITH(kwargs_json(YAML::Load("{x: .inf}")),
                    "'.inf': JSON has no inf or NaN; pass it as a string");
}
