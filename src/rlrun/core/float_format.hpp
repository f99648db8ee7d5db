#pragma once
// Python's repr() of a float: the shortest text that reads back to the same double, with
// ".0" on integral values ("21.0", "0.98", "1e-05"). Used wherever rlrun writes numbers that
// SB3 users' Python tools read (monitor.csv, resolved config.yaml).
#include <string>

namespace rlrun {

std::string python_float_repr(double value);

// A float32 with 9 significant digits ("%.9g"): enough for every float32 to read back
// exactly (FLT_DECIMAL_DIG), so a file of observations and actions can be compared bit for
// bit with what another program computes (`rlrun eval --trajectory`).
std::string float32_text(float value);

}  // namespace rlrun
