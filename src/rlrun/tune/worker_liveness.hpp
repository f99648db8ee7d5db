#pragma once
// Whether the worker running a trial still lives, so that a trial whose worker was killed
// (kill -9, a node lost, a Slurm job cancelled) is re-queued instead of staying RUNNING for ever.
// Each rlrun worker records, in its trial's system attribute "rlrun:worker", its host name,
// process id and the process's start time (/proc/<pid>/stat, field 22), and touches a heartbeat
// file <journal>.workers/<worker id> every kHeartbeatInterval seconds.
//   * on the same host: the worker lives while a process with that pid and start time exists
//     (the pid alone could have been reused) — known at once;
//   * on another host (a Slurm array across nodes sharing the study file): while its heartbeat
//     file is younger than kHeartbeatTimeout.
// Optuna's own heartbeat (RDB storages only) has the same purpose; its journal storage has none.
#include <atomic>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "rlrun/core/dir_handle.hpp"

namespace rlrun::tune {

inline constexpr double kHeartbeatInterval = 10.0;  // seconds
inline constexpr double kHeartbeatTimeout = 120.0;  // seconds without a beat: the worker is gone

// {"id", "host", "pid", "start"} of this process.
nlohmann::json this_worker(const std::string& worker_id);
// True when the worker `record` (from this_worker) still runs. `journal`: the study file.
bool worker_alive(const nlohmann::json& record, const std::string& journal);

// Touches the heartbeat file from a thread of its own while it lives; removes it at the end.
// Throws RuntimeFailure when <journal>.workers is a link or the file cannot be written.
class Heartbeat {
 public:
  Heartbeat(const std::string& journal, const std::string& worker_id);
  ~Heartbeat();
  Heartbeat(const Heartbeat&) = delete;
  Heartbeat& operator=(const Heartbeat&) = delete;

 private:
  DirHandle dir_;     // <journal>.workers
  std::string name_;  // the worker id: the heartbeat file's name
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace rlrun::tune
