#pragma once
// Python's repr() of a float: the shortest text that reads back to the same double, with
// ".0" on integral values ("21.0", "0.98", "1e-05"). Used wherever rlrun writes numbers that
// SB3 users' Python tools read (monitor.csv, resolved config.yaml).
#include <string>

namespace rlrun {

std::string python_float_repr(double value);

}  // namespace rlrun
