// The optional components (runtime/components/optional_components.hpp, CMakeLists.txt): the table CMake
// generates must name exactly the envs its folders register, or a build that leaves a component
// out would answer "unknown environment" for an env it forgot (or hide one it does not own).
// The build without them is checked by scripts/tests/test_minimal_build.sh.
#include <catch2/catch.hpp>

#include <set>
#include <string>

#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/components/optional_components.hpp"

using namespace rlrun;

TEST_CASE("each optional component declares exactly the env ids its folders register",
          "[components]") {
  REQUIRE(optional_components().size() >= 4);
  for (const OptionalComponent& component : optional_components()) {
    INFO(component.option);
    CHECK(component.built);  // the tests are built only when every component is
    std::set<std::string> registered;
    for (const std::string& folder : component.folders) {
      const EnvEntries entries = env_folder_entries(folder);
      CHECK_FALSE(entries.empty());
      for (const EnvEntry& entry : entries) registered.insert(entry.id);
    }
    CHECK(registered == std::set<std::string>(component.env_ids.begin(), component.env_ids.end()));
    CHECK_FALSE(component.packages.empty());
    for (const std::string& id : component.env_ids) {
      CHECK(unbuilt_component_of(id) == nullptr);
      // A family's member: python:x:Y, gymnasium:x:Y, ...; a live object's number.
      const std::string member = id == "python-object:" ? id + "1" : id + "x:Y";
      CHECK(builtin_registry().find_env(id.back() == ':' ? member : id) != nullptr);
    }
  }
}

TEST_CASE("an env of a component left out is refused at env.id with the option and packages",
          "[components]") {
  const OptionalComponent sumo{"RLRUN_WITH_SUMO",     "the SUMO traffic envs",
                               "sumo libpugixml-dev", false,
                               {"traffic"},           {"TrafficSignal-v0"}};
  const std::string message = unbuilt_env_message("TrafficSignal-v0", sumo);
  CHECK_THAT(message, Catch::Contains("TrafficSignal-v0 is not built into this rlrun"));
  CHECK_THAT(message, Catch::Contains("-DRLRUN_WITH_SUMO=ON"));
  CHECK_THAT(message, Catch::Contains("sumo libpugixml-dev"));
}
