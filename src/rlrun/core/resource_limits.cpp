#include "rlrun/core/resource_limits.hpp"
#include "rlrun/core/plural.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>

namespace rlrun {

namespace {

std::string gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GB", bytes / 1e9);
  return text;
}

// Files a run keeps open besides its envs' (logs, CSVs, checkpoints, ffmpeg pipes, libraries).
constexpr int kBaseOpenFiles = 64;
// Files one env may keep open: its monitor file, and a simulator's socket and log.
constexpr int kFilesPerEnv = 3;

}  // namespace

int64_t physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page_size = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_size <= 0) return 0;
  return static_cast<int64_t>(pages) * page_size;
}

std::string memory_problem(double bytes, const std::string& what) {
  const int64_t memory = physical_memory_bytes();
  if (memory <= 0 || bytes <= static_cast<double>(memory)) return "";
  return what + " needs " + gigabytes(bytes) + " of memory, this machine has " +
         gigabytes(static_cast<double>(memory));
}

void check_open_files(int n_envs, const ConfigNode& node) {
  const rlim_t needed = static_cast<rlim_t>(kBaseOpenFiles + kFilesPerEnv * n_envs);
  rlimit limit{};
  if (getrlimit(RLIMIT_NOFILE, &limit) != 0 || limit.rlim_cur >= needed) return;
  if (limit.rlim_max == RLIM_INFINITY || limit.rlim_max >= needed) {
    limit.rlim_cur = needed;
    if (setrlimit(RLIMIT_NOFILE, &limit) == 0) return;
  }
  node.fail("with " + count_of(n_envs, "env") + ", rlrun needs up to " + std::to_string(needed) +
            " open files (a monitor file per env, plus a simulator's socket), but this process may "
            "open " +
            std::to_string(limit.rlim_max) + " (`ulimit -n`): use fewer envs or raise the limit");
}

}  // namespace rlrun
