#pragma once
// A SUMO network file (.net.xml) parsed with pugixml, for the readers of its lights
// (signal_programs.hpp) and its roads (network_geometry.hpp).
#include <pugixml.hpp>

#include <string>

#include "rlrun/core/errors.hpp"
#include "rlrun/envs/sumo/sumo_xml_guard.hpp"

namespace rlrun::traffic {

// The <net> element of `path`, parsed into `doc`. Throws ConfigError naming the file when it
// cannot be read, is not a SUMO network, or declares a DOCTYPE (sumo_xml_guard.hpp).
inline pugi::xml_node load_net_file(const std::string& path, pugi::xml_document& doc) {
  check_sumo_xml(path);
  const pugi::xml_parse_result parsed = doc.load_file(path.c_str());
  if (!parsed)
    throw ConfigError(path + ": not a readable SUMO network (" + parsed.description() +
                      " at byte " + std::to_string(parsed.offset) + ")");
  const pugi::xml_node net = doc.child("net");
  if (!net) throw ConfigError(path + ": not a SUMO network (no <net> element)");
  return net;
}

}  // namespace rlrun::traffic
