#include "rlrun/envs/sumo/network_scenario.hpp"

#include <pugixml.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "rlrun/core/config_fields.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/quoted_text.hpp"
#include "rlrun/core/shipped_data.hpp"
#include "rlrun/envs/sumo/sumo_xml_guard.hpp"

namespace rlrun::traffic {

namespace fs = std::filesystem;

namespace {

// check_routes_fit reads a route file whole; randomTrips' files for a city-day are ~100 MB.
constexpr size_t kMaxRouteFileBytes = size_t{1} << 30;

std::string number_text(double v) {
  std::ostringstream out;
  out.precision(12);
  out << v;
  return out.str();
}

std::vector<std::string> split_list(const std::string& text) {
  // SUMO's file lists: comma (or space) separated.
  std::vector<std::string> out;
  std::string item;
  for (char c : text + ",") {
    if (c == ',' || c == ' ') {
      if (!item.empty()) out.push_back(item);
      item.clear();
    } else {
      item += c;
    }
  }
  return out;
}

std::string resolved(const fs::path& base, const std::string& file) {
  return (base / file).lexically_normal().string();
}

// A <time> value of a .sumocfg in seconds: a number, or SUMO's [[days:]hours:]minutes:seconds.
double sumocfg_seconds(const std::string& path, const char* key, const std::string& text) {
  std::vector<double> parts;
  bool ok = !text.empty();
  for (size_t start = 0; ok && start <= text.size();) {
    const size_t end = std::min(text.find(':', start), text.size());
    double part = 0;
    const auto [stop, error] = std::from_chars(text.data() + start, text.data() + end, part);
    ok = error == std::errc() && stop == text.data() + end && std::isfinite(part) && part >= 0;
    parts.push_back(part);
    start = end + 1;
  }
  if (!ok || parts.size() > 4)
    throw ConfigError(path + ": <time><" + key + " value=\"" + quoted_text(text, 40) +
                      "\">: not a time (seconds >= 0, or [[days:]hours:]minutes:seconds)");
  static const double kFactor[] = {86400, 3600, 60, 1};  // of days, hours, minutes, seconds
  double total = 0;
  for (size_t i = 0; i < parts.size(); ++i) total += parts[i] * kFactor[4 - parts.size() + i];
  return total;
}

// A .sumocfg's <input> files (relative to it) and <time>; only what is set is changed.
void read_sumocfg(const std::string& path, NetworkScenario& s) {
  check_sumo_config(path);  // before anything parses it: no DOCTYPE, nor in what it names
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_file(path.c_str());
  if (!parsed)
    throw ConfigError(path + ": not a readable SUMO configuration (" + parsed.description() + ")");
  const pugi::xml_node cfg = doc.first_child();
  const fs::path base = fs::path(path).parent_path();
  const auto value = [&](const char* section, const char* key) -> std::string {
    const pugi::xml_node n = cfg.child(section).child(key);
    return n ? n.attribute("value").as_string() : "";
  };
  const std::string net = value("input", "net-file");
  if (net.empty()) throw ConfigError(path + ": <input><net-file value=...> is missing");
  s.files.net = resolved(base, net);
  for (const std::string& f : split_list(value("input", "route-files")))
    s.files.routes.push_back(resolved(base, f));
  for (const std::string& f : split_list(value("input", "additional-files")))
    s.files.additionals.push_back(resolved(base, f));
  if (s.begin < 0 && !value("time", "begin").empty())
    s.begin = sumocfg_seconds(path, "begin", value("time", "begin"));
  if (s.end < 0 && !value("time", "end").empty())
    s.end = sumocfg_seconds(path, "end", value("time", "end"));
}

void require_file(const std::string& path, const std::string& what) {
  if (!fs::is_regular_file(path))
    throw RuntimeFailure("traffic scenario: the " + what + " " + path + " does not exist");
}

int line_of(const std::string& text, ptrdiff_t offset) {
  return 1 + static_cast<int>(std::count(
                 text.begin(),
                 text.begin() + std::min<ptrdiff_t>(offset, static_cast<ptrdiff_t>(text.size())),
                 '\n'));
}

}  // namespace

NetworkScenario load_network_scenario(const std::string& path) {
  std::string file = find_data_file(path);
  if (!fs::exists(file))
    throw RuntimeFailure("traffic scenario " + path +
                         " does not exist (a scenarios/*.yaml file "
                         "or a SUMO .sumocfg)");
  NetworkScenario s;
  if (fs::path(file).extension() == ".sumocfg") {
    s.name = fs::path(file).stem().string();
    s.sumocfg = s.files.sumocfg = file;
    read_sumocfg(file, s);
  } else {
    const ConfigNode root = ConfigNode::load_file(file);
    if (!root.is_map())
      root.fail(
          "a traffic scenario is a map: name, net_file, route_files, begin, end (or sumocfg)");
    decode(root, s);
    const fs::path base = fs::path(file).parent_path();
    if (!s.sumocfg.empty()) {
      if (!s.net_file.empty())
        root.child("net_file").fail("give either sumocfg or net_file (+ route_files), not both");
      s.files.sumocfg = resolved(base, s.sumocfg);
      if (!fs::is_regular_file(s.files.sumocfg))
        root.child("sumocfg").fail(s.files.sumocfg + " does not exist");
      read_sumocfg(s.files.sumocfg, s);
    } else {
      if (s.net_file.empty())
        root.fail("net_file: missing (the SUMO network), or sumocfg: a SUMO configuration");
      s.files.net = resolved(base, s.net_file);
      if (!fs::is_regular_file(s.files.net))
        root.child("net_file").fail(s.files.net + " does not exist");
      check_sumo_xml(s.files.net);
      for (size_t i = 0; i < s.route_files.size(); ++i) {
        s.files.routes.push_back(resolved(base, s.route_files[i]));
        if (!fs::is_regular_file(s.files.routes.back()))
          root.child("route_files").fail(s.files.routes.back() + " does not exist");
        check_sumo_xml(s.files.routes.back());
      }
      for (const std::string& f : s.additional_files) {
        s.files.additionals.push_back(resolved(base, f));
        if (!fs::is_regular_file(s.files.additionals.back()))
          root.child("additional_files").fail(s.files.additionals.back() + " does not exist");
        check_sumo_xml(s.files.additionals.back());
      }
    }
    if (!(s.scale > 0)) root.child("scale").fail("must be > 0");
    if (s.begin < 0 && root.has("begin")) root.child("begin").fail("must be >= 0");
    if (s.end >= 0 && s.begin >= 0 && s.begin >= s.end)
      root.child(root.has("end") ? "end" : "begin")
          .fail("begin (" + number_text(s.begin) + " s) must be before end (" + number_text(s.end) +
                " s)");
  }
  if (s.begin < 0) s.begin = 0;
  if (s.end < 0) s.end = s.begin + 3600;
  if (s.begin >= s.end)
    throw ConfigError(file + ": begin (" + number_text(s.begin) + " s) must be before end (" +
                      number_text(s.end) + " s)");
  require_file(s.files.net, "network");
  for (const std::string& f : s.files.routes) require_file(f, "route file");
  for (const std::string& f : s.files.additionals) require_file(f, "additional file");
  if (s.files.routes.empty() && s.files.additionals.empty())
    throw ConfigError(file + ": no route_files: the scenario has no traffic");
  return s;
}

std::vector<std::string> scenario_arguments(const NetworkScenario& s,
                                            const std::vector<std::string>& more_additionals) {
  std::vector<std::string> args;
  const auto join = [](const std::vector<std::string>& files) {
    std::string out;
    for (const std::string& f : files) out.append(out.empty() ? "" : ",").append(f);
    return out;
  };
  std::vector<std::string> additionals = s.files.additionals;
  additionals.insert(additionals.end(), more_additionals.begin(), more_additionals.end());
  if (!s.files.sumocfg.empty()) {
    args = {"-c", s.files.sumocfg};
    if (!more_additionals.empty()) args.insert(args.end(), {"-a", join(additionals)});
  } else {
    args = {"-n", s.files.net};
    if (!s.files.routes.empty()) args.insert(args.end(), {"-r", join(s.files.routes)});
    if (!additionals.empty()) args.insert(args.end(), {"-a", join(additionals)});
  }
  args.insert(args.end(), {"--begin", number_text(s.begin), "--end", number_text(s.end)});
  return args;
}

void check_routes_fit(const std::vector<std::string>& route_files,
                      const std::vector<std::string>& edges,
                      const std::map<std::string, std::vector<std::string>>& successors) {
  const std::set<std::string> known(edges.begin(), edges.end());
  for (const std::string& file : route_files) {
    const std::string text = read_sumo_xml(file, kMaxRouteFileBytes);
    pugi::xml_document doc;
    const pugi::xml_parse_result parsed = doc.load_buffer(text.data(), text.size());
    if (!parsed)
      throw ConfigError(file + ":" + std::to_string(line_of(text, parsed.offset)) +
                        ": not a readable SUMO route file (" + parsed.description() + ")");
    // Depth-first over every element: routes may sit inside <vehicle>/<flow> or at the top.
    struct Walker : pugi::xml_tree_walker {
      const std::set<std::string>* known;
      const std::map<std::string, std::vector<std::string>>* successors;
      std::string unknown, where, gap;
      ptrdiff_t offset = 0;
      bool check(const pugi::xml_node& node, const char* attribute, bool list) {
        const pugi::xml_attribute a = node.attribute(attribute);
        if (!a) return true;
        const std::vector<std::string> ids =
            list ? split_list(a.as_string()) : std::vector<std::string>{a.as_string()};
        for (const std::string& id : ids)
          if (!known->count(id)) {
            unknown = id;
            where = std::string("<") + node.name() + " " + attribute + ">";
            offset = node.offset_debug();
            return false;
          }
        return true;
      }
      bool for_each(pugi::xml_node& node) override {
        const std::string name = node.name();
        if (name == "route") {
          if (!check(node, "edges", true)) return false;
          // Consecutive edges must be connected in the net.
          const std::vector<std::string> ids = split_list(node.attribute("edges").as_string());
          for (size_t i = 1; i < ids.size(); ++i) {
            const auto next = successors->find(ids[i - 1]);
            if (next == successors->end() ||
                std::find(next->second.begin(), next->second.end(), ids[i]) == next->second.end()) {
              gap = "edge '" + ids[i - 1] + "' does not lead to '" + ids[i] + "'";
              offset = node.offset_debug();
              return false;
            }
          }
          return true;
        }
        if (name == "trip" || name == "flow" || name == "vehicle")
          return check(node, "from", false) && check(node, "to", false) && check(node, "via", true);
        return true;
      }
    } walker;
    walker.known = &known;
    walker.successors = &successors;
    doc.traverse(walker);
    if (!walker.gap.empty())
      throw ConfigError(file + ":" + std::to_string(line_of(text, walker.offset)) +
                        ": a <route> whose " + quoted_text(walker.gap, 300) +
                        " in the network: the route file does not fit the network");
    if (!walker.unknown.empty())
      throw ConfigError(file + ":" + std::to_string(line_of(text, walker.offset)) + ": " +
                        walker.where + " names edge '" + quoted_text(walker.unknown) +
                        "', which the network does not have: the route file does not fit the "
                        "network" +
                        quoted_text(did_you_mean(walker.unknown, edges), 300));
  }
}

}  // namespace rlrun::traffic
