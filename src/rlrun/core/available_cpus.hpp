#pragma once
// How many CPUs this process may use (`--threads auto`): the smaller of its affinity mask
// (taskset, numactl, Slurm's CPU binding) and its cgroup's CPU quota (docker --cpus, systemd's
// CPUQuota, Kubernetes limits), rounded up — never the machine's count alone, which a
// container or a batch job may see in full while being allowed a part of it.
#include <optional>
#include <string>

namespace rlrun {

int available_cpus();

// The pieces, for tests. Each returns the quota in whole CPUs (rounded up), or nullopt when
// the text sets no limit or does not parse.
// cgroup v2 `cpu.max`: "max 100000" (no limit) or "<quota> <period>", in microseconds.
std::optional<int> cpus_of_cgroup_v2_max(const std::string& text);
// cgroup v1 `cpu.cfs_quota_us` ("-1": no limit) and `cpu.cfs_period_us`.
std::optional<int> cpus_of_cgroup_v1(const std::string& quota_text, const std::string& period_text);

}  // namespace rlrun
