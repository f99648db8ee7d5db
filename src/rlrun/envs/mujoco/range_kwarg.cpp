#include "rlrun/envs/mujoco/range_kwarg.hpp"

#include <limits>
#include <string>

#include "rlrun/core/ascii_lower.hpp"
#include "rlrun/core/float_format.hpp"

namespace rlrun::mujoco {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// YAML 1.2's core schema: [-+]?(.inf|.Inf|.INF); as_double reads every other number and
// refuses NaN.
double bound(const ConfigNode& n) {
  if (!n.is_scalar()) n.fail("expected a number");
  const std::string text = ascii_lower(n.as_string());
  if (text == ".inf" || text == "+.inf") return kInfinity;
  if (text == "-.inf") return -kInfinity;
  if (text.find("inf") != std::string::npos)
    n.fail("expected a number, .inf or -.inf, got '" + n.as_string() + "'");
  return n.as_double();
}

YAML::Node encode_bound(double value) {
  if (value == kInfinity) return YAML::Node(".inf");
  if (value == -kInfinity) return YAML::Node("-.inf");
  return YAML::Node(python_float_repr(value));
}

}  // namespace

void decode(const ConfigNode& n, RangeKwarg& out) {
  if (!n.is_sequence() || n.size() != 2)
    n.fail("expected [low, high], a list of two numbers, e.g. [0.7, .inf] (.inf: no bound)");
  const double low = bound(n.at(0));
  const double high = bound(n.at(1));
  if (!(low <= high))
    n.fail("expected [low, high] with low <= high (low must not be above high), got [" +
           python_float_repr(low) + ", " + python_float_repr(high) + "]");
  out = {low, high};
}

YAML::Node encode(const RangeKwarg& range) {
  YAML::Node seq(YAML::NodeType::Sequence);
  seq.push_back(encode_bound(range.low));
  seq.push_back(encode_bound(range.high));
  seq.SetStyle(YAML::EmitterStyle::Flow);
  return seq;
}

}  // namespace rlrun::mujoco
