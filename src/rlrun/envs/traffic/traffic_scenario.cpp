#include "rlrun/envs/traffic/traffic_scenario.hpp"

#include <filesystem>

#include "rlrun/core/config_fields.hpp"
#include "rlrun/core/errors.hpp"

namespace rlrun {

namespace fs = std::filesystem;

std::string default_traffic_scenario() {
  return std::string(RLRUN_DATA_DIR) + "/scenarios/single_intersection.yaml";
}

namespace {

std::string existing(const std::string& path) {
  if (fs::exists(path)) return path;
  const fs::path in_source = fs::path(RLRUN_DATA_DIR) / path;
  if (fs::path(path).is_relative() && fs::exists(in_source)) return in_source.string();
  throw RuntimeFailure("traffic scenario " + path + " does not exist (a scenarios/*.yaml file "
                       "or a SUMO .sumocfg)");
}

}  // namespace

TrafficScenario load_traffic_scenario(const std::string& path) {
  const std::string file = existing(path);
  TrafficScenario scenario;
  if (fs::path(file).extension() == ".sumocfg") {
    scenario.name = fs::path(file).stem().string();
    scenario.sumocfg = scenario.sumocfg_path = file;
    return scenario;
  }
  const ConfigNode root = ConfigNode::load_file(file);
  if (!root.is_map()) root.fail("a scenario file is a map with name, description, sumocfg, scale");
  decode(root, scenario);
  if (scenario.sumocfg.empty()) root.fail("sumocfg: missing (the SUMO configuration to run)");
  if (!(scenario.scale > 0)) root.child("scale").fail("must be > 0");
  const fs::path sumocfg = fs::path(file).parent_path() / scenario.sumocfg;
  if (!fs::exists(sumocfg))
    root.child("sumocfg").fail(sumocfg.string() + " does not exist");
  scenario.sumocfg_path = sumocfg.lexically_normal().string();
  return scenario;
}

}  // namespace rlrun
