#pragma once
// A SumoConnection whose SUMO is driven by a worker process (rlrun-sumo-worker,
// apps/sumo_worker/; messages in worker_protocol.hpp): what lets a traffic env run one SUMO
// per env even with backend: libsumo (SUMO keeps one simulation per process), and step several
// envs' SUMOs at the same time (start_advance() returns at once; finish_advance() collects).
//
// The worker is started with fork + exec (the child makes only system calls before exec:
// rlrun's other threads may hold locks), dies with rlrun (PR_SET_PDEATHSIG) and ends when this
// object closes its socket. A worker or SUMO that dies is a RuntimeFailure with SUMO's last
// output, never a hang; every wait for an answer polls (core/worker_wait.hpp), so Ctrl-C stops
// rlrun while SUMO starts or while a worker hangs.
#include <sys/types.h>

#include <memory>
#include <string>
#include <vector>

#include "rlrun/envs/sumo/sumo_connection.hpp"
#include "rlrun/envs/sumo/worker_protocol.hpp"

namespace rlrun::traffic {

class SumoWorker : public SumoConnection {
 public:
  // Starts the worker and, in it, SUMO with `backend` and `launch`. Throws RuntimeFailure
  // naming what to install when the worker program or SUMO is missing.
  SumoWorker(const std::string& backend, const SumoLaunch& launch);
  ~SumoWorker() override;
  SumoWorker(const SumoWorker&) = delete;
  SumoWorker& operator=(const SumoWorker&) = delete;

  void subscribe(const std::vector<std::string>& lanes,
                 const std::vector<std::string>& edges) override;
  void subscribe_vehicles(const std::string& junction, NetworkReading& out) override;
  void advance(double time, NetworkReading& out) override;
  // advance() in two halves: the worker runs SUMO while the caller starts other workers.
  void start_advance(double time);
  void finish_advance(NetworkReading& out);
  void set_light_state(const std::string& tls, const std::string& state) override;
  void switch_light(const std::string& tls, const std::string& yellow, int yellow_seconds,
                    const std::string& green) override;
  void use_program(const std::string& tls, const std::string& program_id) override;
  void finish() override;
  std::string output_tail() const override { return tail_; }
  // SUMO's process: the `sumo` child of the worker (traci) or the worker itself (libsumo).
  pid_t pid() const override { return finished_ ? -1 : sumo_pid_; }
  pid_t worker_pid() const { return worker_; }

 private:
  void send(const std::vector<char>& framed);
  // The answer to the last request that has one; throws RuntimeFailure on kError, Interrupted
  // (worker_wait.hpp) on Ctrl-C. `starting`: the answer to kStart (SUMO loads its network).
  wire::Reader answer(bool starting = false);
  void stop();

  int fd_ = -1;
  pid_t worker_ = -1;
  pid_t sumo_pid_ = -1;
  bool finished_ = false;
  bool hung_ = false;  // a wait for it was interrupted: killed at once, not given 2 s
  std::string tail_;   // SUMO's last output, from the worker's last error
};

}  // namespace rlrun::traffic
