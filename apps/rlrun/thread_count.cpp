#include "thread_count.hpp"

#include <charconv>
#include <cstdlib>
#include <system_error>

#include "rlrun/core/available_cpus.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/quoted_text.hpp"

namespace rlrun::cli {

int thread_count(const std::string& text, const std::string& source) {
  if (text == "auto") return available_cpus();
  int value = 0;
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc() || stop != end || value < 1 || value > kMaxThreads)
    throw UsageError(source + " must be a whole number from 1 to " + std::to_string(kMaxThreads) +
                     " or auto (the CPUs this process may use), got '" + quoted_text(text) + "'");
  return value;
}

int threads_for_run(const std::string& option) {
  if (!option.empty()) return thread_count(option, "--threads");
  if (const char* env = std::getenv("RLRUN_THREADS"); env != nullptr && *env != '\0')
    return thread_count(env, "RLRUN_THREADS");
  return available_cpus();
}

}  // namespace rlrun::cli
