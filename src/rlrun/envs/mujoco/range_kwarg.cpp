#include "rlrun/envs/mujoco/range_kwarg.hpp"

#include <algorithm>
#include <cctype>
#include <limits>
#include <string>

#include "rlrun/core/float_format.hpp"

namespace rlrun::mujoco {

namespace {

// YAML's spellings of infinity (.inf, -.inf, .Inf, +.INF) and Python's repr (inf, -inf), so a
// resolved config written by Python tools reads back too; anything else is an ordinary number.
double bound(const ConfigNode& n) {
  if (n.is_scalar()) {
    std::string text = n.yaml().Scalar();
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    const double inf = std::numeric_limits<double>::infinity();
    if (text == ".inf" || text == "+.inf" || text == "inf" || text == "+inf") return inf;
    if (text == "-.inf" || text == "-inf") return -inf;
  }
  return n.as_double();
}

YAML::Node encode_bound(double v) {
  if (v == std::numeric_limits<double>::infinity()) return YAML::Node(".inf");
  if (v == -std::numeric_limits<double>::infinity()) return YAML::Node("-.inf");
  return YAML::Node(python_float_repr(v));
}

}  // namespace

void decode(const ConfigNode& n, RangeKwarg& out) {
  if (!n.is_sequence() || n.size() != 2)
    n.fail("expected a list of two numbers [low, high], e.g. [0.2, 1.0] (.inf for no bound)");
  const double low = bound(n.at(0)), high = bound(n.at(1));
  if (low > high)
    n.fail("low must not be above high, got [" + python_float_repr(low) + ", " +
           python_float_repr(high) + "]");
  out = {low, high};
}

YAML::Node encode(const RangeKwarg& v) {
  YAML::Node seq(YAML::NodeType::Sequence);
  seq.push_back(encode_bound(v.low));
  seq.push_back(encode_bound(v.high));
  seq.SetStyle(YAML::EmitterStyle::Flow);
  return seq;
}

}  // namespace rlrun::mujoco
