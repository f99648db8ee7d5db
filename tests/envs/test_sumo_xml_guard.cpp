// SUMO inputs with a DOCTYPE are refused before anything parses them (an entity "billion
// laughs" of 1 KB cost 34 s, 1.2 GB and a 300 MB error in SUMO's Xerces), wherever the file
// comes from: the .sumocfg, a network, a route or additional file it names, a file pulled in
// with <include href>, gzip-compressed or not. Text quoted from a file in an error is one line of
// at most 200 characters. The real binary and real SUMO for the commands; the checker itself for
// the cases around it.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "envs/python_env_runner.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/envs/sumo/sumo_xml_guard.hpp"
#include "runtime/peak_memory_bound.hpp"

using namespace rlrun;
using namespace rlrun::testing;

namespace {

const std::string kSingle = std::string(RLRUN_SOURCE_DIR) + "/sumo_data/single_intersection/";
const std::string kGrid = std::string(RLRUN_SOURCE_DIR) + "/sumo_data/grid4x4/";

// An internal DTD whose entity expands to 10^levels copies of "ha", and `root` using it in an
// attribute (where SUMO's parser expands it).
std::string entity_bomb(const std::string& root, int levels = 7) {
  std::string text = "<?xml version=\"1.0\"?>\n<!DOCTYPE " + root + " [\n <!ENTITY a0 \"ha\">\n";
  for (int i = 1; i <= levels; ++i) {
    text += " <!ENTITY a" + std::to_string(i) + " \"";
    for (int k = 0; k < 10; ++k) text += "&a" + std::to_string(i - 1) + ";";
    text += "\">\n";
  }
  return text + "]>\n";
}

// The shipped single-intersection scenario's configuration with other inputs.
std::string sumocfg(const std::string& routes, const std::string& begin = "0") {
  return "<configuration>\n  <input>\n    <net-file value=\"" + kSingle +
         "single.net.xml\"/>\n"
         "    <route-files value=\"" +
         routes + "\"/>\n    <additional-files value=\"" + kSingle +
         "tls.tll.xml\"/>\n  </input>\n  <time>\n    <begin value=\"" + begin +
         "\"/>\n    <end value=\"3600\"/>\n  </time>\n</configuration>\n";
}

std::string write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::string refusal(const std::string& path) {
  try {
    check_sumo_xml(path);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("A billion-laughs .sumocfg is refused quickly with a short error", "[traffic]") {
  TempDir dir("sumo_bomb_cfg");
  const std::string cfg =
      write(dir / "bomb.sumocfg",
            entity_bomb("configuration") + sumocfg(kSingle + "routes.rou.xml", "&a7;"));
  // TrafficSignal-v0 hands the .sumocfg to SUMO, whose parser expanded the entity (10^7 times).
  const auto r = run_command_measured(std::string(RLRUN_BINARY) +
                                      " eval --env TrafficSignal-v0 --policy fixed-time "
                                      "--episodes 1 --set env.kwargs.scenario=" +
                                      cfg);
  INFO(r.output.substr(0, 2000));
  CHECK(r.exit_code == 2);
  CHECK(r.output.size() < 1000);
  CHECK(r.output.find(cfg + ":2: a markup declaration (<!DOCTYPE ...): rlrun refuses DOCTYPE") !=
        std::string::npos);
  CHECK(r.peak_rss_kb < peak_rss_bound_kb(200 * 1024));
}

TEST_CASE("A billion-laughs network file is refused before pugixml or SUMO reads it", "[traffic]") {
  TempDir dir("sumo_bomb_net");
  std::string net = read_text(kGrid + "grid4x4.net.xml");
  net.replace(net.find("<net "), 5, "<net junk=\"&a7;\" ");
  const std::string bomb =
      write(dir / "bomb.net.xml", entity_bomb("net") + net.substr(net.find("<net ")));
  const std::string scenario =
      write(dir / "bomb.yaml", "name: bomb\nnet_file: bomb.net.xml\nroute_files: [" + kGrid +
                                   "grid4x4.rou.xml]\nbegin: 0\nend: 100\n");
  const auto r = run_command_measured(std::string(RLRUN_BINARY) +
                                      " eval --env TrafficNetwork-v0 --policy fixed-time "
                                      "--episodes 1 --set env.kwargs.scenario=" +
                                      scenario);
  INFO(r.output.substr(0, 2000));
  CHECK(r.exit_code == 2);
  CHECK(r.output.size() < 1000);
  CHECK(r.output.find(bomb + ":2: a markup declaration (<!DOCTYPE") != std::string::npos);
  CHECK(r.peak_rss_kb < peak_rss_bound_kb(200 * 1024));
}

TEST_CASE("Every SUMO input is checked: named by a .sumocfg or included or gzip-compressed",
          "[traffic]") {
  TempDir dir("sumo_bomb_inputs");
  const std::string routes = read_text(kSingle + "routes.rou.xml");
  const std::string bomb_routes = write(dir / "bomb.rou.xml", entity_bomb("routes", 2) + routes);

  SECTION("a route file a .sumocfg names") {
    const std::string cfg = write(dir / "a.sumocfg", sumocfg("bomb.rou.xml"));
    try {
      check_sumo_config(cfg);
      FAIL("accepted");
    } catch (const ConfigError& e) {
      CHECK(std::string(e.what()).find(bomb_routes + ":2: a markup declaration") == 0);
      CHECK(std::string(e.what()).find("(named by " + cfg + ", <route-files>)") !=
            std::string::npos);
    }
  }
  SECTION("a file an additional file includes, and what that includes") {
    write(dir / "inner.add.xml", "<additional><include href=\"bomb.rou.xml\"/></additional>\n");
    const std::string outer = write(
        dir / "outer.add.xml", "<additional>\n<include href='inner.add.xml' />\n</additional>\n");
    const std::string message = refusal(outer);
    CHECK(message.find(bomb_routes + ":2: a markup declaration") == 0);
    CHECK(message.find("(included by " + dir / "inner.add.xml" + ") (included by " + outer + ")") !=
          std::string::npos);
  }
  SECTION("a gzip-compressed network (SUMO reads .gz by its content)") {
    const std::string text = entity_bomb("net", 2) + "<net/>\n";
    gzFile gz = gzopen((dir / "bomb.net.xml").c_str(), "wb");
    gzwrite(gz, text.data(), static_cast<unsigned>(text.size()));
    gzclose(gz);
    CHECK(refusal(dir / "bomb.net.xml").find(":2: a markup declaration (<!DOCTYPE") !=
          std::string::npos);
  }
  SECTION("an include cycle, UTF-16, a FIFO") {
    write(dir / "a.xml", "<additional><include href=\"b.xml\"/></additional>");
    write(dir / "b.xml", "<additional><include href=\"a.xml\"/></additional>");
    CHECK(refusal(dir / "a.xml").find("includes itself") != std::string::npos);
    write(dir / "u16.xml", std::string("\xFF\xFE<\0n\0e\0t\0/\0>\0", 14));
    CHECK(refusal(dir / "u16.xml").find("UTF-16") != std::string::npos);
    write(dir / "enc.xml", "<?xml version=\"1.0\" encoding=\"UTF-16\"?><net/>");
    CHECK(refusal(dir / "enc.xml").find("declares encoding 'UTF-16'") != std::string::npos);
    REQUIRE(mkfifo((dir / "fifo.xml").c_str(), 0600) == 0);
    CHECK(refusal(dir / "fifo.xml").find("is not a regular file") != std::string::npos);
  }
  SECTION("files that only mention a DOCTYPE are accepted") {
    CHECK(refusal(write(dir / "ok.xml",
                        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<!-- <!DOCTYPE x> -->\n"
                        "<routes note=\"<!DOCTYPE y>\"><![CDATA[<!ENTITY z \"\">]]>\n"
                        "<?pi <!DOCTYPE?></routes>\n")) == "");
    CHECK(refusal(kGrid + "grid4x4.net.xml") == "");
    CHECK_NOTHROW(check_sumo_config(kSingle + "single.sumocfg"));
  }
}

TEST_CASE("Text quoted from a SUMO input is one short line", "[traffic]") {
  TempDir dir("sumo_long_attribute");
  SECTION("an edge id of 1 MB in a route file (rlrun's own check)") {
    const std::string id(1 << 20, 'e');
    const std::string routes = write(
        dir / "long.rou.xml", "<routes>\n<route id=\"r\" edges=\"" + id + "\"/>\n</routes>\n");
    const std::string scenario =
        write(dir / "long.yaml",
              "name: long\nnet_file: " + kGrid +
                  "grid4x4.net.xml\nroute_files: [long.rou.xml]\nbegin: 0\nend: 100\n");
    const auto r = run_command(std::string(RLRUN_BINARY) +
                               " eval --env TrafficNetwork-v0 --policy fixed-time --episodes 1 "
                               "--set env.kwargs.scenario=" +
                               scenario);
    INFO(r.output.substr(0, 2000));
    CHECK(r.exit_code == 2);
    CHECK(r.output.find(routes + ":2: <route edges> names edge 'eeee") != std::string::npos);
    CHECK(r.output.find("eee...'") != std::string::npos);  // cut (core/quoted_text.hpp)
    CHECK(r.output.size() < 1500);
  }
  SECTION("a vehicle type of 100 KB that SUMO quotes in its error") {
    std::string routes = read_text(kSingle + "routes.rou.xml");
    routes.replace(routes.find("<routes>") + 8, 0,
                   "\n<trip id=\"bad\" type=\"" + std::string(100000, 't') +
                       "\" from=\"n_in\" to=\"s_out\" depart=\"0\"/>");
    write(dir / "type.rou.xml", routes);
    const std::string cfg = write(dir / "type.sumocfg", sumocfg("type.rou.xml"));
    const auto r = run_command(std::string(RLRUN_BINARY) +
                               " eval --env TrafficSignal-v0 --policy fixed-time --episodes 1 "
                               "--set env.kwargs.scenario=" +
                               cfg);
    INFO(r.output.substr(0, 3000));
    CHECK(r.exit_code == 1);
    CHECK(r.output.find("tttttttt") != std::string::npos);  // SUMO's line, cut
    CHECK(r.output.size() < 5000);
  }
}

TEST_CASE("A .sumocfg <time> value that is not a time is named with its file", "[traffic]") {
  TempDir dir("sumo_bad_begin");
  const std::string cfg = write(dir / "abc.sumocfg", sumocfg(kSingle + "routes.rou.xml", "abc"));
  const auto r = run_command(std::string(RLRUN_BINARY) +
                             " eval --env TrafficNetwork-v0 --policy fixed-time --episodes 1 "
                             "--set env.kwargs.scenario=" +
                             cfg);
  INFO(r.output);
  CHECK(r.exit_code == 2);
  CHECK(r.output.find(cfg + ": <time><begin value=\"abc\">: not a time") != std::string::npos);
  CHECK(r.output.find("stod") == std::string::npos);  // was all it said: "error: stod"
}
