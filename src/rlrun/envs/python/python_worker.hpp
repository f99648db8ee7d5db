#pragma once
// One Python interpreter running worker.py (an env in its own process, as SB3's
// SubprocVecEnv), and the socket to it. Started as `PYTHON -c <worker.py> 3` with the socket
// as fd 3, stdin from /dev/null, stdout/stderr shared with rlrun (the env's prints and, on a
// crash, faulthandler's Python stack appear in rlrun's output).
//
// No worker outlives rlrun: the destructor closes the socket (the worker exits) and reaps the
// process, killing it after a grace period; the child asks the kernel for SIGKILL when rlrun
// dies (prctl PR_SET_PDEATHSIG: `kill -9` of rlrun, a crash); and it ignores SIGINT, so a
// Ctrl-C, which the terminal sends to the whole process group, stops rlrun (which saves its
// checkpoint and then closes its workers) rather than killing envs under it. A second Ctrl-C
// stops rlrun even while an env hangs in step().
#include <sys/types.h>

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace rlrun {

class PythonWorker {
 public:
  // Starts the worker (fork + exec; fast: the interpreter then starts in parallel with the
  // caller). Throws RuntimeFailure when `python` is not an executable / on PATH.
  PythonWorker(const std::string& python, const std::string& script);
  ~PythonWorker();
  PythonWorker(const PythonWorker&) = delete;
  PythonWorker& operator=(const PythonWorker&) = delete;

  // Send / receive exactly these bytes; false when the worker has gone (EOF, broken pipe).
  bool write(std::span<const std::byte> data);
  bool read(std::span<std::byte> data);

  pid_t pid() const { return pid_; }
  const std::string& python() const { return python_; }  // the resolved interpreter path

  // After write/read failed: how the process ended ("exited with status 1", "was killed by
  // signal 11 (Segmentation fault)"), waiting a moment for it; kills it if it still runs.
  std::string how_it_ended();

  // The size of this worker's requests (python_protocol::request_bytes), known after the
  // handshake; stop() sends its close request in that size.
  void set_request_bytes(size_t bytes) { request_bytes_ = bytes; }

  // Asks the worker to close its env and exit, and reaps it (the destructor does it too).
  void stop();

 private:
  std::string python_;
  int fd_ = -1;
  pid_t pid_ = -1;
  int status_ = 0;
  bool reaped_ = false;
  size_t request_bytes_ = 0;
  std::vector<std::byte> buffer_ = std::vector<std::byte>(size_t{1} << 16);  // read()'s
  size_t buffer_start_ = 0, buffer_end_ = 0;  // 0: before the handshake (no close request then)
  bool wait_for_exit(double seconds);
  // After a recv: true when it only timed out (the worker is still busy; try again), after
  // throwing RuntimeFailure if the user has pressed Ctrl-C twice meanwhile.
  bool waited_out(ssize_t n) const;
};

}  // namespace rlrun
