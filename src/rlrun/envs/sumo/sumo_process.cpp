#include "rlrun/envs/sumo/sumo_process.hpp"

#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <libsumo/libtraci.h>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/private_temp_dir.hpp"
#include "rlrun/core/quoted_text.hpp"
#include "rlrun/core/worker_wait.hpp"

namespace rlrun {

namespace {

// A TCP port the kernel considers free right now (bound to port 0, then released).
int free_port() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) throw RuntimeFailure("cannot open a socket to find a free port for SUMO");
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = 0;
  socklen_t length = sizeof address;
  if (bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
      getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
    close(fd);
    throw RuntimeFailure("cannot find a free TCP port for SUMO");
  }
  const int port = ntohs(address.sin_port);
  close(fd);
  return port;
}

std::string next_label() {
  static std::atomic<int> counter{0};
  return "rlrun" + std::to_string(getpid()) + "_" + std::to_string(counter++);
}

bool process_alive(pid_t pid) {
  int status = 0;
  return waitpid(pid, &status, WNOHANG) == 0;
}

}  // namespace

SumoProcess::SumoProcess(const Options& options)
    : dir_("rlrun-sumo-", PrivateTempDir::RemoveStale::kYes), label_(next_label()) {
  // A socket whose SUMO has gone must fail with an error (reported with SUMO's output), not
  // kill rlrun with SIGPIPE.
  struct sigaction current;
  if (sigaction(SIGPIPE, nullptr, &current) == 0 && current.sa_handler == SIG_DFL)
    std::signal(SIGPIPE, SIG_IGN);
  const std::string binary = find_executable(options.binary);
  if (binary.empty())
    throw RuntimeFailure("cannot run SUMO: '" + options.binary +
                         "' was not found; install the Debian package 'sumo' (apt install sumo)");
  if (options.inputs.empty() && !std::filesystem::exists(options.config))
    throw RuntimeFailure("SUMO scenario " + options.config + " does not exist");
  const int port = free_port();
  std::vector<std::string> args{binary, "--remote-port", std::to_string(port)};
  for (std::string& a : sumo_arguments(options)) args.push_back(std::move(a));
  // Everything the child needs is prepared before fork(): rlrun may run thread-pool workers,
  // and the child of a threaded process may only call async-signal-safe functions
  // (no malloc) until exec.
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // SUMO's output goes to a fresh file in this process's private directory (O_EXCL, no
  // symlink followed), opened here so the child only has to dup2 it.
  log_path_ = dir_.file("sumo.log");
  const int log_fd = dir_.create_file("sumo.log");
  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ < 0) {
    close(log_fd);
    throw RuntimeFailure("cannot start SUMO (fork failed)");
  }
  if (pid_ == 0) {
    // SUMO dies with rlrun, whatever kills rlrun.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(1);
    setpgid(0, 0);                // Ctrl-C at the terminal is rlrun's to handle, not SUMO's
    dup2(log_fd, STDOUT_FILENO);  // the copies are not close-on-exec; log_fd itself is
    dup2(log_fd, STDERR_FILENO);
    execv(argv[0], argv.data());
    _exit(127);
  }
  close(log_fd);
  // SUMO listens after loading the network (milliseconds); poll instead of libtraci's
  // one-second retry sleep, and for Ctrl-C: SUMO starts at every reset, so a first Ctrl-C lets
  // it load within the grace period (core/worker_wait.hpp) and training reach its safe point.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  WorkerWait starting;
  starting.who = "SUMO (pid " + std::to_string(pid_) + ")";
  starting.what = "to accept the TraCI connection";
  while (true) {
    try {
      check_worker_wait(starting);
    } catch (const Interrupted&) {
      kill(pid_, SIGKILL);  // still loading: nothing of it to keep
      waitpid(pid_, nullptr, 0);
      pid_ = -1;
      throw;
    }
    try {
      libtraci::Simulation::init(port, 0, "localhost", label_);
      connected_ = true;
      break;
    } catch (const std::exception&) {
      if (!process_alive(pid_)) {
        pid_ = -1;
        throw RuntimeFailure("SUMO exited before accepting the TraCI connection; its output:\n" +
                             output_tail());
      }
      if (std::chrono::steady_clock::now() > deadline) {
        stop();
        throw RuntimeFailure("SUMO did not accept the TraCI connection within 30 s; its output:\n" +
                             output_tail());
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
}

SumoProcess::~SumoProcess() { stop(); }  // then dir_ goes, with the log

void SumoProcess::activate() const { libtraci::Simulation::switchConnection(label_); }

void SumoProcess::stop() {
  if (connected_) {
    connected_ = false;
    try {
      activate();
      libtraci::Simulation::close();
    } catch (const std::exception&) {
      // Already gone (SUMO died): reaping below is all that is left.
    }
  }
  if (pid_ <= 0) return;
  for (int i = 0; i < 2000 && process_alive(pid_); ++i)  // SUMO writes its outputs, then exits
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  if (process_alive(pid_)) {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  pid_ = -1;
}

// The log's last 64 KiB, each line cut to 200 characters: SUMO quotes its inputs in its
// messages, and a crafted input can make one line of them megabytes long.
std::string SumoProcess::output_tail(int lines) const {
  constexpr std::streamoff kTailBytes = 64 << 10;
  std::ifstream in(log_path_, std::ios::binary | std::ios::ate);
  const std::streamoff size = in ? static_cast<std::streamoff>(in.tellg()) : 0;
  std::string text(static_cast<size_t>(std::min(size, kTailBytes)), '\0');
  in.seekg(size - static_cast<std::streamoff>(text.size()));
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  std::vector<std::string> all;
  std::stringstream stream(text);
  for (std::string line; std::getline(stream, line);) all.push_back(line);
  if (size > kTailBytes && !all.empty()) all.front().insert(0, "...");  // a line's end
  std::string tail;
  for (size_t i = all.size() > static_cast<size_t>(lines) ? all.size() - lines : 0; i < all.size();
       ++i)
    tail += "  " + quoted_text(all[i]) + "\n";
  return tail.empty() ? "  (no output)\n" : tail;
}

}  // namespace rlrun
