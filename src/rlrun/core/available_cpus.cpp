#include "rlrun/core/available_cpus.hpp"

#include <sched.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

namespace rlrun {

namespace {

// A kernel interface file (a few bytes; read with a bound all the same), "" when unreadable.
std::string read_small_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) return "";
  std::string text(4096, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<size_t>(in.gcount()));
  return text;
}

std::optional<int> whole_cpus(double quota, double period) {
  if (!(quota > 0) || !(period > 0)) return std::nullopt;
  return std::max(1, static_cast<int>(std::ceil(quota / period - 1e-9)));
}

std::optional<double> number(const std::string& text) {
  std::istringstream in(text);
  double value = 0;
  if (!(in >> value)) return std::nullopt;
  return value;
}

// The cgroup paths of this process (/proc/self/cgroup): v2's ("0::/path") and v1's cpu
// controller's ("N:cpu,cpuacct:/path").
struct CgroupPaths {
  std::optional<std::string> v2, v1_cpu;
};

CgroupPaths own_cgroups() {
  CgroupPaths paths;
  std::istringstream lines(read_small_file("/proc/self/cgroup"));
  for (std::string line; std::getline(lines, line);) {
    const size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    const std::string path = line.substr(second + 1);
    if (line.compare(0, first, "0") == 0 && controllers.empty()) paths.v2 = path;
    std::istringstream names(controllers);
    for (std::string name; std::getline(names, name, ',');)
      if (name == "cpu") paths.v1_cpu = path;
  }
  return paths;
}

// The smallest quota on the way from `path` up to the hierarchy's root: a limit anywhere
// above a cgroup applies to it too.
template <class QuotaAt>
std::optional<int> tightest_quota(std::string path, QuotaAt quota_at) {
  std::optional<int> tightest;
  while (true) {
    if (const std::optional<int> cpus = quota_at(path))
      tightest = tightest ? std::min(*tightest, *cpus) : *cpus;
    if (path.empty() || path == "/") break;
    const size_t slash = path.find_last_of('/');
    path = slash == std::string::npos || slash == 0 ? "/" : path.substr(0, slash);
  }
  return tightest;
}

std::optional<int> cgroup_quota() {
  const CgroupPaths own = own_cgroups();
  std::optional<int> v2, v1;
  if (own.v2)
    v2 = tightest_quota(*own.v2, [](const std::string& path) {
      return cpus_of_cgroup_v2_max(read_small_file("/sys/fs/cgroup" + path + "/cpu.max"));
    });
  if (own.v1_cpu)
    v1 = tightest_quota(*own.v1_cpu, [](const std::string& path) {
      for (const char* mount : {"/sys/fs/cgroup/cpu", "/sys/fs/cgroup/cpu,cpuacct"}) {
        const std::string dir = std::string(mount) + path;
        if (const std::optional<int> cpus =
                cpus_of_cgroup_v1(read_small_file(dir + "/cpu.cfs_quota_us"),
                                  read_small_file(dir + "/cpu.cfs_period_us")))
          return cpus;
      }
      return std::optional<int>();
    });
  if (v2 && v1) return std::min(*v2, *v1);
  return v2 ? v2 : v1;
}

int affinity_cpus() {
  cpu_set_t cpus;
  if (sched_getaffinity(0, sizeof(cpus), &cpus) == 0) return std::max(1, CPU_COUNT(&cpus));
  return std::max(1u, std::thread::hardware_concurrency());
}

}  // namespace

std::optional<int> cpus_of_cgroup_v2_max(const std::string& text) {
  std::istringstream in(text);
  std::string quota, period;
  if (!(in >> quota >> period) || quota == "max") return std::nullopt;
  const std::optional<double> q = number(quota), p = number(period);
  return q && p ? whole_cpus(*q, *p) : std::nullopt;
}

std::optional<int> cpus_of_cgroup_v1(const std::string& quota_text,
                                     const std::string& period_text) {
  const std::optional<double> q = number(quota_text), p = number(period_text);
  return q && p ? whole_cpus(*q, *p) : std::nullopt;  // a quota of -1 means no limit
}

int available_cpus() {
  const int affinity = affinity_cpus();
  const std::optional<int> quota = cgroup_quota();
  return quota ? std::min(affinity, *quota) : affinity;
}

}  // namespace rlrun
