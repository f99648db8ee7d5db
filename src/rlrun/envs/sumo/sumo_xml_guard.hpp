#pragma once
// SUMO's inputs (.sumocfg, .net.xml, .rou.xml, additional files) are XML, read by SUMO's Xerces
// parser and, for the network files, by pugixml in rlrun. Xerces expands the entities a
// document type declaration defines: a "billion laughs" .sumocfg of 1 KB (ten entities of ten
// references each) became ~10^9 characters, 34 s, 1.2 GB and a 300 MB error message; an
// external entity (<!ENTITY x SYSTEM "/etc/...">) reads another file. No SUMO file needs a DTD
// (SUMO describes its formats with XML Schemas, sumo.dlr.de/xsd), so rlrun refuses any
// <!DOCTYPE ...> (or other <!...> declaration) in every SUMO input before anything parses it
// (docs/security.md, "SUMO scenarios").
//
// What is checked: the file itself (gzip-compressed too: SUMO reads .gz by content), every file
// it pulls in with <include href="..."> (SUMO's GenericSAXHandler reads those anywhere, relative
// to the including file), and for a .sumocfg every existing file any of its options names.
// Besides a declaration, a file is refused when it is not a regular file, is UTF-16/32 or
// declares an encoding that is not ASCII-compatible (the check reads bytes), is larger than
// 4 GiB uncompressed, or includes files more than 16 deep or in a cycle.
#include <string>
#include <vector>

namespace rlrun {

// One SUMO XML file and its includes. Throws ConfigError naming the file (and the file that
// named it) and the reason.
void check_sumo_xml(const std::string& path);

// A SUMO configuration: itself, then every file its options name (relative to it), except the
// outputs SUMO writes.
void check_sumo_config(const std::string& sumocfg);

// SUMO's command line (sumo_arguments): the files of -c, -n, -r, -a (and their long names).
void check_sumo_command_inputs(const std::vector<std::string>& args);

// The whole text of a (possibly gzip-compressed) SUMO XML file that check_sumo_xml accepts, at
// most `max_bytes` bytes (ConfigError beyond): for rlrun's own readers.
std::string read_sumo_xml(const std::string& path, size_t max_bytes);

}  // namespace rlrun
