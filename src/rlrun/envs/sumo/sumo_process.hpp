#pragma once
// One SUMO simulation owned by one env, driven over TraCI with SUMO's own C++ client
// (libtracicpp, Debian package `sumo`). The process is started here, not by libtraci's
// Simulation::start, so that rlrun knows its pid and output: `sumo -c CFG --remote-port P
// --seed S --no-step-log ...` on a free port (argv, no shell), stdout/stderr into a log file,
// connected under a label of its own (libtraci keeps one connection per label: several envs,
// several SUMOs). The log lives in a private temporary directory (core/private_temp_dir.hpp)
// that goes with the object, also when the constructor fails: the error quotes the log's last
// lines first.
//
// No SUMO outlives rlrun: the destructor closes the connection and reaps the process (killing
// it after a grace period), and the child asks the kernel for SIGKILL when rlrun dies
// (prctl PR_SET_PDEATHSIG), which covers crashes and `kill -9`.
#include <sys/types.h>

#include <cstdint>
#include <string>
#include <vector>

#include "rlrun/core/find_executable.hpp"
#include "rlrun/core/private_temp_dir.hpp"
#include "rlrun/envs/sumo/sumo_connection.hpp"

namespace rlrun {

class SumoProcess {
 public:
  using Options = SumoLaunch;

  // Throws RuntimeFailure naming the Debian package when the binary is missing, and with the
  // tail of SUMO's output when it exits before accepting the connection.
  explicit SumoProcess(const Options& options);
  ~SumoProcess();
  SumoProcess(const SumoProcess&) = delete;
  SumoProcess& operator=(const SumoProcess&) = delete;

  // Makes this simulation the target of the next libtraci calls (one label per process).
  void activate() const;
  const std::string& label() const { return label_; }
  pid_t pid() const { return pid_; }

  // Closes the connection (SUMO completes its output files and exits) and reaps the process,
  // killing it after a grace period. The destructor does it too.
  void stop();

  // The last lines SUMO wrote, for error messages ("SUMO stopped: ...").
  std::string output_tail(int lines = 10) const;

 private:
  PrivateTempDir dir_;  // first: made before anything can fail, removed after the process ends
  std::string label_;
  std::string log_path_;
  pid_t pid_ = -1;
  bool connected_ = false;
};

}  // namespace rlrun
