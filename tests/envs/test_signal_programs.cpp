// envs/traffic_network/signal_programs: the lights of a SUMO network read from its .net.xml,
// and sumo-rl's green phases and yellow transitions (traffic_signal.py build_phases), on
// hand-made programs and on a grid that SUMO's own netgenerate builds.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include <libsumo/libtraci.h>

#include "rlrun/core/errors.hpp"
#include "rlrun/envs/sumo/sumo_connection.hpp"
#include "rlrun/envs/traffic_network/signal_programs.hpp"
#include "runtime/cli_runner.hpp"

using namespace rlrun;
using namespace rlrun::traffic;
using namespace rlrun::testing;

namespace {

// A network of one light, three controlled links, with the given phases.
std::string one_light_net(const std::vector<std::string>& states) {
  std::string xml =
      "<net version=\"1.9\">\n  <tlLogic id=\"J1\" type=\"static\" programID=\"0\" offset=\"0\">\n";
  for (const std::string& s : states) xml += "    <phase duration=\"10\" state=\"" + s + "\"/>\n";
  xml +=
      "  </tlLogic>\n"
      "  <connection from=\"N\" to=\"S\" fromLane=\"0\" toLane=\"0\" tl=\"J1\" linkIndex=\"0\"/>\n"
      "  <connection from=\"N\" to=\"E\" fromLane=\"1\" toLane=\"0\" tl=\"J1\" linkIndex=\"1\"/>\n"
      "  <connection from=\"W\" to=\"E\" fromLane=\"0\" toLane=\"0\" tl=\"J1\" linkIndex=\"2\"/>\n"
      "  <connection from=\"X\" to=\"Y\" fromLane=\"0\" toLane=\"0\"/>\n"
      "</net>\n";
  return xml;
}

std::string write(const TempDir& dir, const std::string& name, const std::string& text) {
  const std::string path = dir / name;
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST_CASE("signal programs: green phases, yellow transitions and lanes as sumo-rl builds them",
          "[traffic_network]") {
  TempDir dir("signal_programs");
  // Greens: no 'y' and not all 'r'/'s'. The yellow and all-red phases are not actions.
  const std::string net =
      write(dir, "one.net.xml", one_light_net({"GGr", "yyr", "rrr", "rsG", "srs", "gGG"}));
  const std::vector<TrafficLightProgram> lights = read_signal_programs(net);
  REQUIRE(lights.size() == 1);
  const TrafficLightProgram& light = lights[0];
  CHECK(light.id == "J1");
  CHECK(light.program_id == "0");
  CHECK(light.num_links == 3);
  CHECK(light.phases.size() == 6);
  CHECK(light.incoming_lanes == std::vector<std::string>{"N_0", "N_1", "W_0"});
  CHECK(light.outgoing_lanes == std::vector<std::string>{"S_0", "E_0"});

  const SignalControl control = derive_signal_control(light);
  CHECK(control.green_states == std::vector<std::string>{"GGr", "rsG", "gGG"});
  // 'G'/'g' followed by 'r'/'s' turns 'y'; everything else keeps green i's character.
  CHECK(control.yellow_states[0][1] == "yyr");  // GGr -> rsG
  CHECK(control.yellow_states[0][2] == "GGr");  // GGr -> gGG: nothing stops
  CHECK(control.yellow_states[1][0] == "rsy");  // rsG -> GGr
  CHECK(control.yellow_states[1][2] == "rsG");  // rsG -> gGG
  CHECK(control.yellow_states[2][0] == "gGy");  // gGG -> GGr
  CHECK(control.yellow_states[2][1] == "yyG");  // gGG -> rsG: g -> r and G -> s
  CHECK(control.yellow_states[1][1].empty());

  CHECK(select_lights(lights, {}, net).size() == 1);
  CHECK(select_lights(lights, {"J1"}, net).front().id == "J1");
}

TEST_CASE("signal programs: a netgenerate grid's lights, lanes and phases", "[traffic_network]") {
  TempDir dir("signal_grid");
  const std::string net = dir / "grid.net.xml";
  const CommandResult made = run_command(
      "netgenerate --grid --grid.number 4 --grid.length 200 --default.lanenumber 2 "
      "--tls.guess true --no-turnarounds true -o '" +
      net + "' 2>&1");
  INFO(made.output);
  REQUIRE(made.exit_code == 0);
  std::ifstream in(net);
  std::stringstream text;
  text << in.rdbuf();
  const std::string xml = text.str();
  // What the file holds, counted independently of the reader.
  std::set<std::string> lane_ids;
  const std::regex lane(R"re(<lane id="([^"]+)")re");
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), lane); it != std::sregex_iterator();
       ++it)
    lane_ids.insert((*it)[1]);
  const std::regex logic(R"re(<tlLogic id="([^"]+)")re");
  const auto n_logics =
      std::distance(std::sregex_iterator(xml.begin(), xml.end(), logic), std::sregex_iterator());
  REQUIRE(n_logics >= 4);

  const std::vector<TrafficLightProgram> lights = read_signal_programs(net);
  CHECK(static_cast<long>(lights.size()) == n_logics);
  for (const TrafficLightProgram& light : lights) {
    INFO(light.id);
    CHECK(light.num_links > 0);
    CHECK_FALSE(light.incoming_lanes.empty());
    CHECK_FALSE(light.outgoing_lanes.empty());
    for (const std::string& l : light.incoming_lanes) CHECK(lane_ids.count(l) == 1);
    for (const std::string& l : light.outgoing_lanes) CHECK(lane_ids.count(l) == 1);
    for (const SignalPhase& p : light.phases)
      CHECK(static_cast<int>(p.state.size()) == light.num_links);
    const SignalControl control = derive_signal_control(light);
    CHECK(control.green_states.size() >= 2);
    for (size_t i = 0; i < control.green_states.size(); ++i)
      for (size_t j = 0; j < control.green_states.size(); ++j)
        if (i != j) CHECK(control.yellow_states[i][j].find('y') != std::string::npos);
  }
}

TEST_CASE(
    "signal programs: the reader agrees with a running SUMO (TraCI) on lights, lanes and phases",
    "[traffic_network]") {
  TempDir dir("signal_traci");
  const std::string net = dir / "grid.net.xml";
  REQUIRE(run_command("netgenerate --grid --grid.number 3 --grid.length 150 --default.lanenumber 2 "
                      "--tls.guess true -o '" +
                      net + "' 2>&1")
              .exit_code == 0);
  std::ofstream(dir / "grid.sumocfg") << "<configuration><input><net-file value=\"grid.net.xml\"/>"
                                         "</input></configuration>\n";
  const std::vector<TrafficLightProgram> lights = read_signal_programs(net);
  REQUIRE_FALSE(lights.empty());

  SumoLaunch launch;
  launch.config = dir / "grid.sumocfg";
  launch.end_time = 10;
  const std::unique_ptr<SumoConnection> sumo = start_traci_connection(launch);
  // One connection: it is libtraci's current one.
  std::vector<std::string> ids = libtraci::TrafficLight::getIDList();
  std::vector<std::string> read_ids;
  for (const TrafficLightProgram& light : lights) read_ids.push_back(light.id);
  std::sort(ids.begin(), ids.end());
  std::sort(read_ids.begin(), read_ids.end());
  CHECK(read_ids == ids);
  for (const TrafficLightProgram& light : lights) {
    INFO(light.id);
    // sumo-rl: list(dict.fromkeys(getControlledLanes(id))).
    std::vector<std::string> lanes;
    for (const std::string& lane : libtraci::TrafficLight::getControlledLanes(light.id))
      if (std::find(lanes.begin(), lanes.end(), lane) == lanes.end()) lanes.push_back(lane);
    CHECK(light.incoming_lanes == lanes);
    std::set<std::string> out;
    for (const auto& link : libtraci::TrafficLight::getControlledLinks(light.id))
      if (!link.empty()) out.insert(link.front().toLane);
    CHECK(std::set<std::string>(light.outgoing_lanes.begin(), light.outgoing_lanes.end()) == out);
    const auto logics = libtraci::TrafficLight::getAllProgramLogics(light.id);
    REQUIRE_FALSE(logics.empty());
    REQUIRE(logics.front().phases.size() == light.phases.size());
    for (size_t k = 0; k < light.phases.size(); ++k) {
      CHECK(logics.front().phases[k]->state == light.phases[k].state);
      CHECK(logics.front().phases[k]->duration == light.phases[k].duration);
    }
  }
  sumo->finish();
}

TEST_CASE("signal programs: bad networks and ts_ids are clear errors", "[traffic_network]") {
  TempDir dir("signal_errors");
  // A network without lights (netgenerate without --tls.guess).
  const std::string plain = dir / "plain.net.xml";
  REQUIRE(run_command("netgenerate --grid --grid.number 2 -o '" + plain + "' 2>&1").exit_code == 0);
  const auto none = read_signal_programs(plain);
  CHECK(none.empty());
  CHECK_THROWS_WITH(select_lights(none, {}, plain), Catch::Contains("no traffic light"));

  const std::string net = write(dir, "one.net.xml", one_light_net({"GGr", "rrG"}));
  const auto lights = read_signal_programs(net);
  CHECK_THROWS_WITH(select_lights(lights, {"J2"}, net),
                    Catch::Contains("'J2' is not a traffic light") && Catch::Contains("J1"));
  CHECK_THROWS_AS(read_signal_programs(write(dir, "junk.xml", "not xml <<")), ConfigError);
  CHECK_THROWS_WITH(read_signal_programs(write(dir, "other.xml", "<routes/>")),
                    Catch::Contains("no <net> element"));
  CHECK_THROWS_AS(read_signal_programs(dir / "missing.net.xml"), ConfigError);
  // A light that is never green, and a state too short for the links it controls.
  const auto red = read_signal_programs(write(dir, "red.net.xml", one_light_net({"rrr", "yyr"})));
  CHECK_THROWS_WITH(derive_signal_control(red.front()), Catch::Contains("no green phase"));
  CHECK_THROWS_WITH(read_signal_programs(write(dir, "short.net.xml", one_light_net({"GG", "rr"}))),
                    Catch::Contains("controlled links"));
}
