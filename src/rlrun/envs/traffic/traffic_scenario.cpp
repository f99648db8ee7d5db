#include "rlrun/envs/traffic/traffic_scenario.hpp"

#include <filesystem>

#include "rlrun/core/config_fields.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/shipped_data.hpp"
#include "rlrun/envs/traffic/sumo_xml_guard.hpp"

namespace rlrun {

namespace fs = std::filesystem;

std::string default_traffic_scenario() {
  return (fs::path(shipped_data_dir()) / "scenarios" / "single_intersection.yaml").string();
}

namespace {

std::string existing(const std::string& path) {
  const std::string file = find_data_file(path);
  if (fs::exists(file)) return file;
  throw RuntimeFailure("traffic scenario " + path +
                       " does not exist (a scenarios/*.yaml file "
                       "or a SUMO .sumocfg)");
}

}  // namespace

TrafficScenario load_traffic_scenario(const std::string& path) {
  const std::string file = existing(path);
  TrafficScenario scenario;
  if (fs::path(file).extension() == ".sumocfg") {
    scenario.name = fs::path(file).stem().string();
    scenario.sumocfg = scenario.sumocfg_path = file;
    check_sumo_config(file);  // no DOCTYPE in it or the files it names (sumo_xml_guard.hpp)
    return scenario;
  }
  const ConfigNode root = ConfigNode::load_file(file);
  if (!root.is_map()) root.fail("a scenario file is a map with name, description, sumocfg, scale");
  decode(root, scenario);
  if (scenario.sumocfg.empty()) root.fail("sumocfg: missing (the SUMO configuration to run)");
  if (!(scenario.scale > 0)) root.child("scale").fail("must be > 0");
  const fs::path sumocfg = fs::path(file).parent_path() / scenario.sumocfg;
  if (!fs::exists(sumocfg)) root.child("sumocfg").fail(sumocfg.string() + " does not exist");
  scenario.sumocfg_path = sumocfg.lexically_normal().string();
  check_sumo_config(scenario.sumocfg_path);
  return scenario;
}

}  // namespace rlrun
