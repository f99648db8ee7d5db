#pragma once
// `--threads N|auto` and RLRUN_THREADS: how many threads one run uses. Read here, in main()'s
// layer only; the count reaches the layers below as an ExecutionContext
// (core/execution_context.hpp).
#include <string>

namespace rlrun::cli {

// At most this many threads: a typo such as --threads 80000 must not start 80 000 threads.
inline constexpr int kMaxThreads = 4096;

// "auto" -> the CPUs this process may use (core/available_cpus.hpp); "N" -> N in [1,
// kMaxThreads]. Throws UsageError naming `source` ("--threads", "RLRUN_THREADS") otherwise.
int thread_count(const std::string& text, const std::string& source);

// --threads when given (non-empty `option`), else RLRUN_THREADS when set, else auto.
int threads_for_run(const std::string& option);

}  // namespace rlrun::cli
