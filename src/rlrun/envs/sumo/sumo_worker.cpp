#include "rlrun/envs/sumo/sumo_worker.hpp"

#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <thread>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/process_settings.hpp"
#include "rlrun/core/quoted_text.hpp"
#include "rlrun/core/worker_spawn.hpp"
#include "rlrun/core/worker_wait.hpp"
#include "rlrun/envs/sumo/worker_protocol.hpp"

namespace rlrun::traffic {

namespace {

constexpr int kWorkerFd = 3;

std::string worker_path() {
  return rlrun_helper_path("rlrun-sumo-worker", process_settings().sumo_worker);
}

}  // namespace

SumoWorker::SumoWorker(const std::string& backend, const SumoLaunch& launch) {
  const std::string path = worker_path();
  if (access(path.c_str(), X_OK) != 0)
    throw RuntimeFailure("own_process: true needs " + path +
                         " (rlrun's SUMO worker, built and installed with rlrun); it is missing "
                         "or not executable");
  const SpawnedWorker worker =
      spawn_worker({path, std::to_string(kWorkerFd)}, kWorkerFd, "the SUMO worker");
  worker_ = worker.pid;
  fd_ = worker.fd;
  wire::Writer start(wire::kStart);
  start.str(backend)
      .str(launch.binary)
      .strings(launch.inputs)
      .str(std::to_string(launch.seed))
      .f64(launch.scale)
      .strings(launch.extra_args);
  send(start.framed());
  wire::Reader reply(answer(true));
  sumo_pid_ = reply.i32();
}

SumoWorker::~SumoWorker() { stop(); }

void SumoWorker::stop() {
  if (fd_ >= 0) close(fd_);  // the worker reads the end, ends SUMO and exits
  fd_ = -1;
  if (worker_ <= 0) return;
  for (int i = 0; i < 200 && !hung_; ++i) {  // 2 s for SUMO to close its files
    if (waitpid(worker_, nullptr, WNOHANG) == worker_) {
      worker_ = -1;
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  kill(worker_, SIGKILL);
  waitpid(worker_, nullptr, 0);
  worker_ = -1;
}

void SumoWorker::send(const std::vector<char>& framed) {
  if (fd_ < 0 || !wire::send_message(fd_, framed))
    throw RuntimeFailure("the SUMO worker (pid " + std::to_string(worker_) + ") has gone");
}

wire::Reader SumoWorker::answer(bool starting) {
  WorkerWait wait;
  wait.who = "the SUMO worker (pid " + std::to_string(worker_) + ")";
  wait.what = starting ? "to start SUMO" : "in a simulation step";
  // Not WorkerWait::starting: SUMO starts again at every reset, so a start is often what stands
  // between a first Ctrl-C and training's next safe point (a rollout that crosses an episode's
  // end); it gets the grace period of any reply. Stopping here lost the run's work (no model,
  // no checkpoint) in 2 of 3 Ctrl-Cs of a grid4x4 PPO run whose episodes were 120 decisions.
  wait.starting = false;
  const auto poll_for_interrupts = [&] {
    try {
      wait_for_worker(fd_, POLLIN, wait);
    } catch (...) {
      hung_ = true;
      throw;
    }
  };
  std::vector<char> body;
  if (fd_ < 0 || !wire::receive_message(fd_, body, poll_for_interrupts)) {
    int status = 0;
    std::string how = "ended";
    // The socket closes while the worker exits: give the kernel a moment to report how.
    for (int i = 0; i < 100 && worker_ > 0; ++i) {
      if (waitpid(worker_, &status, WNOHANG) == worker_) {
        how = WIFSIGNALED(status) ? "was killed by signal " + std::to_string(WTERMSIG(status))
                                  : "exited with status " + std::to_string(WEXITSTATUS(status));
        if (WIFEXITED(status) && WEXITSTATUS(status) == 127) how += " (it could not be started)";
        const pid_t gone = worker_;
        worker_ = -1;
        throw RuntimeFailure("the SUMO worker (pid " + std::to_string(gone) + ") " + how);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    throw RuntimeFailure("the SUMO worker (pid " + std::to_string(worker_) + ") " + how);
  }
  wire::Reader reader(std::move(body));
  if (reader.u8() == wire::kOk) return reader;
  // kError: the message, then SUMO's last output.
  const std::string message = reader.str();
  const size_t line = message.find('\n');
  tail_ = line == std::string::npos ? std::string() : message.substr(line + 1);
  throw RuntimeFailure(
      quoted_text(line == std::string::npos ? message : message.substr(0, line), 500));
}

void SumoWorker::subscribe(const std::vector<std::string>& lanes,
                           const std::vector<std::string>& edges) {
  wire::Writer w(wire::kSubscribe);
  send(w.strings(lanes).strings(edges).framed());
}

void SumoWorker::subscribe_vehicles(const std::string& junction, NetworkReading& out) {
  wire::Writer w(wire::kSubscribeVehicles);
  send(w.str(junction).framed());
  wire::Reader reply = answer();
  // Subscribing reads the vehicles, not the clock: only advance() moves the time. The worker's
  // reading has not stepped yet at the start of an episode (its time is 0, not the scenario's
  // begin), and a subscription made mid-episode (rlrun record) must not rewind the env's time.
  const double time = out.time;
  wire::read_reading(reply, out);
  out.time = time;
}

void SumoWorker::start_advance(double time) {
  wire::Writer w(wire::kAdvance);
  send(w.f64(time).framed());
}

void SumoWorker::finish_advance(NetworkReading& out) {
  wire::Reader reply = answer();
  wire::read_reading(reply, out);
}

void SumoWorker::advance(double time, NetworkReading& out) {
  start_advance(time);
  finish_advance(out);
}

void SumoWorker::set_light_state(const std::string& tls, const std::string& state) {
  wire::Writer w(wire::kSetLightState);
  send(w.str(tls).str(state).framed());
}

void SumoWorker::switch_light(const std::string& tls, const std::string& yellow, int yellow_seconds,
                              const std::string& green) {
  wire::Writer w(wire::kSwitchLight);
  send(w.str(tls).str(yellow).i32(yellow_seconds).str(green).framed());
}

void SumoWorker::use_program(const std::string& tls, const std::string& program_id) {
  wire::Writer w(wire::kUseProgram);
  send(w.str(tls).str(program_id).framed());
}

void SumoWorker::finish() {
  if (finished_) return;
  wire::Writer w(wire::kFinish);
  send(w.framed());
  answer();
  finished_ = true;
  stop();
}

}  // namespace rlrun::traffic
