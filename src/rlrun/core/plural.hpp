#pragma once
// A count with its noun, singular or plural as English needs it: count_of(1, "env") is
// "1 env", count_of(4, "env") is "4 envs". Every message that counts something goes through
// here, so that no user ever reads "1 episodes".
#include <cstdint>
#include <string>

namespace rlrun {

// `plural` defaults to `singular` + "s"; give it for the irregular ones ("entry", "entries").
inline std::string count_of(int64_t n, const std::string& singular,
                            const std::string& plural = "") {
  std::string text = std::to_string(n);
  text += ' ';
  text += n == 1 || n == -1 ? singular : (plural.empty() ? singular + "s" : plural);
  return text;
}

}  // namespace rlrun
