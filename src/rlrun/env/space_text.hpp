#pragma once
// Text forms of spaces and of their values for people: check-env's reports, `rlrun list ID`,
// messages about observation logs. A Dict is shown key by key, with where each key's floats
// sit in the flat vector (rlrun/space.hpp: keys in sorted order).
#include <span>
#include <string>
#include <vector>

#include "rlrun/space.hpp"

namespace rlrun {

// "[0.5, -1]", or for a Dict "{'goal': [0.5, -1], 'position': [0, 0.25]}".
std::string format_value(const Space& space, std::span<const float> x);

// Why x is not in the space, naming the first Dict key (and entry) outside it, e.g.
// "key 'row' is 7, not in Discrete(4)"; "" when x is inside.
std::string outside_reason(const Space& space, std::span<const float> x);

// describe() as lines: one for most spaces; for a Dict a "Dict (N floats)" line, then one per
// key "'goal': Box(-1.0, 1.0, (2,), float32)  floats [0, 2)".
std::vector<std::string> describe_lines(const Space& space);

// describe_lines() under a label, as the CLI prints spaces: "  <label padded>  <line>\n", the
// further lines of a Dict aligned below the first.
std::string labeled_space(const std::string& label, const Space& space, int label_width);

// The flat layout in words: "4 floats" or "4 floats: 'goal' [0, 2), 'position' [2, 4)".
std::string flat_layout(const Space& space);

}  // namespace rlrun
