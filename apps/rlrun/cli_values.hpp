#pragma once
// Checks of numeric command-line values, with rlrun's own messages. CLI11's stock checks are
// not used: PositiveNumber reports its range with DBL_MAX printed in full (309 digits), and
// CLI11 converts "-1", "18446744073709551616" or "1e23" into an unsigned seed by wrapping it to
// 2^64 - 1 without a word. Each check here is a CLI11 transform: it reads the text as typed,
// refuses it with "<option>: must be ..., got '<text>'" (exit 2), or rewrites it to plain digits
// that the option's C++ type then converts exactly.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <limits>
#include <string>

namespace rlrun::cli {

// The seeds rlrun accepts, everywhere: run.seed is read as a 64-bit signed integer that must not
// be negative (core/config_fields.hpp, decode of uint64_t), so 0 .. 2^63 - 1. Every command
// taking --seed uses the same range, so a seed that evaluates also trains.
inline constexpr uint64_t kMaxSeed = static_cast<uint64_t>(std::numeric_limits<int64_t>::max());

// A seed: plain digits, 0 .. kMaxSeed.
CLI::Validator seed_value();

// An integer in [min, max]. Written as in the config files: 100000, 100_000 or 1e5 (an exact
// integer). The message names the range: "must be an integer >= 1" when max is the type's.
CLI::Validator integer_in(int64_t min, int64_t max = std::numeric_limits<int>::max());

// A finite number in (0, max].
CLI::Validator positive_number(double max);

}  // namespace rlrun::cli
