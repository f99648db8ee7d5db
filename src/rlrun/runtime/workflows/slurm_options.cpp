#include "rlrun/runtime/workflows/slurm_options.hpp"

#include <cstdio>
#include <regex>

namespace rlrun {

bool is_control_char(char c) {
  const auto u = static_cast<unsigned char>(c);
  return u < 0x20 || u == 0x7f;
}

std::string printable_value(const std::string& value) {
  std::string out;
  for (char c : value) {
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (is_control_char(c)) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", static_cast<unsigned char>(c));
      out += hex;
    } else {
      out += c;
    }
  }
  return "'" + out + "'";
}

std::string slurm_value_problem(const std::string& key, const std::string& value) {
  // What sbatch accepts for each option (sbatch(1)), narrowed to characters that mean the same
  // on a `#SBATCH` line as on a command line: no blanks, quotes, backslashes, '#' or control
  // characters, which sbatch's tokenizer would split, unquote or cut.
  static const std::regex time(
      R"(([0-9]+-)?[0-9]+(:[0-9]+){0,2}|[Uu][Nn][Ll][Ii][Mm][Ii][Tt][Ee][Dd]|[Ii][Nn][Ff][Ii][Nn][Ii][Tt][Ee])");
  static const std::regex mem(R"([0-9]+[KMGTkmgt]?)");
  static const std::regex partition(R"([A-Za-z0-9_.,-]+)");
  static const std::regex extra(R"(--[A-Za-z][A-Za-z0-9-]*(=[^\s'"\\#]+)?)");
  bool control = false;
  for (char c : value) control = control || is_control_char(c);
  const std::string why =
      control ? " (it holds a control character: a newline would end the #SBATCH line and start "
                "a command)"
              : "";
  if (key == "time") {
    if (value.empty() || (!control && std::regex_match(value, time))) return "";
    return "time " + printable_value(value) + " is not a Slurm time limit" + why +
           "; write MM, HH:MM:SS or D-HH:MM:SS, e.g. \"01:30:00\" or \"2-00:00:00\"";
  }
  if (key == "mem") {
    if (value.empty() || (!control && std::regex_match(value, mem))) return "";
    return "mem " + printable_value(value) + " is not a Slurm memory size" + why +
           "; write a number with an optional unit K, M, G or T, e.g. 4G or 500M";
  }
  if (key == "partition") {
    if (value.empty() || (!control && std::regex_match(value, partition))) return "";
    return "partition " + printable_value(value) + " is not a Slurm partition name" + why +
           "; use letters, digits, '_', '.', '-' (a list separated by ',')";
  }
  if (key == "extra") {
    if (!control && std::regex_match(value, extra)) return "";
    return "extra " + printable_value(value) + " is not one sbatch option" + why +
           "; write --option or --option=value without blanks, quotes, '\\' or '#', e.g. "
           "\"--qos=short\" (each item becomes one #SBATCH line)";
  }
  if (key == "cpus_per_task") {
    static const std::regex count(R"([1-9][0-9]{0,5})");
    if (std::regex_match(value, count)) return "";
    return "cpus_per_task " + printable_value(value) + " must be an integer >= 1";
  }
  return "unknown slurm option " + key;
}

void check_slurm_options(const ConfigNode& slurm, const SlurmOptions& options) {
  const auto check = [&](const std::string& key, const std::string& value, const ConfigNode& at) {
    const std::string problem = slurm_value_problem(key, value);
    if (!problem.empty()) at.fail(problem);
  };
  check("time", options.time, slurm.child("time"));
  check("mem", options.mem, slurm.child("mem"));
  check("partition", options.partition, slurm.child("partition"));
  check("cpus_per_task", std::to_string(options.cpus_per_task), slurm.child("cpus_per_task"));
  const ConfigNode extra = slurm.child("extra");
  for (size_t i = 0; i < options.extra.size(); ++i)
    check("extra", options.extra[i], i < extra.size() ? extra.at(i) : extra);
}

}  // namespace rlrun
