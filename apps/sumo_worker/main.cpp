// rlrun-sumo-worker FD: drives one SUMO for a traffic env (own_process: true) on behalf of an rlrun process
// (envs/sumo/worker_protocol.hpp has the messages; sumo_worker.cpp starts it).
// With backend: libsumo the simulation runs inside this process, so every env of an rlrun run
// — n_envs copies, the eval env — has a SUMO of its own; with traci this process holds the
// socket to a `sumo` child. Several workers step their SUMOs at the same time.
//
// Dies with rlrun (PR_SET_PDEATHSIG, set by the parent before exec); ignores Ctrl-C, which
// rlrun handles; ends when rlrun closes the socket.
#include <signal.h>
#include <unistd.h>

#include <cstdio>

#include <cstdlib>
#include <exception>
#include <memory>
#include <string>

#include "process_environment.hpp"
#include "rlrun/envs/sumo/sumo_connection.hpp"
#include "rlrun/envs/sumo/worker_protocol.hpp"

using namespace rlrun;
using namespace rlrun::traffic;

namespace {

struct Worker {
  int fd;
  std::unique_ptr<SumoConnection> sumo;
  std::string error;  // the first failure not yet reported
  NetworkReading reading;

  std::string describe(const std::exception& e) const {
    std::string tail;
    try {
      if (sumo) tail = sumo->output_tail();
    } catch (const std::exception&) {
    }
    return std::string(e.what()) + "\n" + tail;
  }

  bool reply_error() {
    wire::Writer w(wire::kError);
    w.str(error);
    return wire::send_message(fd, w.framed());
  }

  SumoConnection& running() {
    if (!sumo) throw std::runtime_error("no simulation (start it first)");
    return *sumo;
  }

  // One request; false when the socket is gone.
  bool serve(wire::Reader& in) {
    const uint8_t op = in.u8();
    const bool answers = op == wire::kStart || op == wire::kSubscribeVehicles ||
                         op == wire::kAdvance || op == wire::kFinish || op == wire::kOutputTail;
    if (op == wire::kOutputTail) {
      wire::Writer w(wire::kOk);
      w.str(sumo ? sumo->output_tail() : std::string());
      return wire::send_message(fd, w.framed());
    }
    if (!error.empty() && op != wire::kStart) return answers ? reply_error() : true;
    try {
      wire::Writer w(wire::kOk);
      switch (op) {
        case wire::kStart: {
          error.clear();
          sumo.reset();
          const std::string backend = in.str();
          SumoLaunch launch;
          launch.binary = in.str();
          launch.inputs = in.strings();
          launch.seed = std::strtoull(in.str().c_str(), nullptr, 10);
          launch.scale = in.f64();
          launch.extra_args = in.strings();
          sumo = start_sumo(backend, launch);
          w.i32(sumo->pid() > 0 ? sumo->pid() : static_cast<int32_t>(getpid()));
          break;
        }
        case wire::kSubscribe: {
          const std::vector<std::string> lanes = in.strings();
          running().subscribe(lanes, in.strings());
          return true;
        }
        case wire::kSubscribeVehicles:
          running().subscribe_vehicles(in.str(), reading);
          wire::write_reading(w, reading);
          break;
        case wire::kAdvance:
          running().advance(in.f64(), reading);
          wire::write_reading(w, reading);
          break;
        case wire::kSetLightState: {
          const std::string tls = in.str();
          running().set_light_state(tls, in.str());
          return true;
        }
        case wire::kSwitchLight: {
          const std::string tls = in.str(), yellow = in.str();
          const int seconds = in.i32();
          running().switch_light(tls, yellow, seconds, in.str());
          return true;
        }
        case wire::kUseProgram: {
          const std::string tls = in.str();
          running().use_program(tls, in.str());
          return true;
        }
        case wire::kFinish: running().finish(); break;
        default: throw std::runtime_error("unknown request " + std::to_string(op));
      }
      return wire::send_message(fd, w.framed());
    } catch (const std::exception& e) {  // TraCI errors, socket errors (tcpip::SocketException)
      error = describe(e);
      return answers ? reply_error() : true;
    }
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "rlrun-sumo-worker is started by rlrun (a traffic env), not by hand\n");
    return 2;
  }
  signal(SIGINT, SIG_IGN);
  signal(SIGPIPE, SIG_IGN);
  try {
    apply_process_environment();  // RLRUN_LIBSUMO_MODULE, as rlrun passed it on
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rlrun-sumo-worker: RLRUN_KERNELS=%s\n", e.what());
    return 2;
  }
  Worker worker{std::atoi(argv[1]), nullptr, {}, {}};
  std::vector<char> body;
  while (wire::receive_message(worker.fd, body)) {
    wire::Reader in(std::move(body));
    try {
      if (!worker.serve(in)) break;
    } catch (const std::exception&) {  // a malformed request: the parent is not rlrun
      break;
    }
  }
  return 0;  // the connection's destructor ends SUMO
}
