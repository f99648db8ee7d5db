#pragma once
// One Python interpreter running worker.py (an env in its own process, as SB3's
// SubprocVecEnv), and the socket to it. Started as `PYTHON -c <worker.py> 3` with the socket
// as fd 3, stdin from /dev/null, stdout/stderr shared with rlrun (the env's prints and, on a
// crash, faulthandler's Python stack appear in rlrun's output).
//
// No worker outlives rlrun: the destructor closes the socket (the worker exits) and reaps the
// process, killing it after a grace period, or at once when it has not finished starting or
// hangs; the child asks the kernel for SIGKILL when rlrun dies (prctl PR_SET_PDEATHSIG: `kill
// -9` of rlrun, a crash, a Ctrl-C before rlrun installs its handlers); and it ignores SIGINT, so
// a Ctrl-C, which the terminal sends to the whole process group, stops rlrun (which saves its
// checkpoint and then closes its workers) rather than killing envs under it. Every wait for the
// worker polls (core/worker_wait.hpp): Ctrl-C stops rlrun while a worker starts or hangs.
#include <sys/types.h>

#include <chrono>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "rlrun/core/worker_wait.hpp"

namespace rlrun {

class PythonWorker {
 public:
  // Starts the worker (fork + exec; fast: the interpreter then starts in parallel with the
  // caller). Throws RuntimeFailure when `python` is not an executable / on PATH.
  PythonWorker(const std::string& python, const std::string& script);
  // A worker that already runs in this process (a thread of the `rlrun` Python package serving
  // a live env object, python_live_env.hpp) at the other end of the connected socket `fd`,
  // which this object now owns. pid() is this process's; stop() closes the socket only.
  struct InProcess {};
  PythonWorker(InProcess, int fd, const std::string& python);
  ~PythonWorker();
  PythonWorker(const PythonWorker&) = delete;
  PythonWorker& operator=(const PythonWorker&) = delete;

  // Send / receive exactly these bytes; false when the worker has gone (EOF, broken pipe).
  // While the worker is silent they wait as `wait` says (Interrupted, a timeout's
  // RuntimeFailure); the worker then counts as hung.
  bool write(std::span<const std::byte> data, const WorkerWait& wait);
  bool read(std::span<std::byte> data, const WorkerWait& wait);

  pid_t pid() const { return pid_; }
  const std::string& python() const { return python_; }  // the resolved interpreter path
  std::chrono::steady_clock::time_point started() const { return started_; }
  // A wait for it ended in an interrupt or timeout: never reused, killed at once.
  bool hung() const { return hung_; }
  // Between a request and the end of its reply (PythonEnv says): a worker stopped then after a
  // Ctrl-C is busy in the env's code, maybe for good, and is killed rather than waited for.
  void set_awaiting_reply(bool awaiting) { awaiting_reply_ = awaiting; }

  // After write/read failed: how the process ended ("exited with status 1", "was killed by
  // signal 11 (Segmentation fault)"), waiting a moment for it; kills it if it still runs.
  std::string how_it_ended();

  // The size of this worker's requests (python_protocol::request_bytes), known after the
  // handshake; stop() sends its close request in that size.
  void set_request_bytes(size_t bytes) { request_bytes_ = bytes; }

  // Asks the worker to close its env and exit, and reaps it (the destructor does it too). A
  // worker that has not finished its handshake, hangs, or is busy after a Ctrl-C is killed at
  // once.
  void stop();

 private:
  std::string python_;
  int fd_ = -1;
  pid_t pid_ = -1;
  int status_ = 0;
  bool reaped_ = false;
  bool in_process_ = false;
  bool hung_ = false;
  bool awaiting_reply_ = false;
  std::chrono::steady_clock::time_point started_;
  size_t request_bytes_ = 0;  // 0: before the handshake (no close request then)
  std::vector<std::byte> buffer_ = std::vector<std::byte>(size_t{1} << 16);  // read()'s
  size_t buffer_start_ = 0, buffer_end_ = 0;
  bool wait_for_exit(double seconds);
  // wait_for_worker, marking the worker hung when it throws.
  void await(short events, const WorkerWait& wait);
};

}  // namespace rlrun
