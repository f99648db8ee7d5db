#include "rlrun/envs/python/python_worker.hpp"

#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <thread>
#include <vector>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/find_executable.hpp"
#include "rlrun/core/interrupt.hpp"
#include "rlrun/core/worker_spawn.hpp"
#include "rlrun/envs/python/python_protocol.hpp"

namespace rlrun {

namespace {

constexpr int kWorkerFd = 3;  // worker.py reads sys.argv[1]; rlrun always passes 3

}  // namespace

PythonWorker::PythonWorker(const std::string& python, const std::string& script) {
  python_ = find_executable(python);
  if (python_.empty())
    throw RuntimeFailure("cannot run the Python interpreter '" + python + "': not an executable" +
                         (python.find('/') == std::string::npos ? " on PATH" : "") +
                         ". Install python3 and numpy (Debian: apt install python3 "
                         "python3-numpy) or set env.python to your virtualenv's python");
  started_ = std::chrono::steady_clock::now();
  const SpawnedWorker worker = spawn_worker({python_, "-c", script, std::to_string(kWorkerFd)},
                                            kWorkerFd, "a Python worker");
  pid_ = worker.pid;
  fd_ = worker.fd;
}

PythonWorker::PythonWorker(InProcess, int fd, const std::string& python)
    : python_(python), fd_(fd), pid_(getpid()), in_process_(true) {
  started_ = std::chrono::steady_clock::now();
}

PythonWorker::~PythonWorker() { stop(); }

void PythonWorker::await(short events, const WorkerWait& wait) {
  try {
    wait_for_worker(fd_, events, wait);
  } catch (...) {
    hung_ = true;
    throw;
  }
}

bool PythonWorker::write(std::span<const std::byte> data, const WorkerWait& wait) {
  size_t done = 0;
  while (done < data.size()) {
    const ssize_t n =
        send(fd_, data.data() + done, data.size() - done, MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      await(POLLOUT, wait);  // the socket's buffer is full: the worker is not reading
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

// Buffered: a reply usually arrives in one piece, so one recv serves its header and body.
bool PythonWorker::read(std::span<std::byte> data, const WorkerWait& wait) {
  size_t done = 0;
  while (done < data.size()) {
    if (buffer_start_ == buffer_end_) {
      const size_t wanted = data.size() - done;
      const bool direct = wanted >= buffer_.size();  // large (a frame): straight into place
      std::byte* into = direct ? data.data() + done : buffer_.data();
      const ssize_t n = recv(fd_, into, direct ? wanted : buffer_.size(), MSG_DONTWAIT);
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
        // A first Ctrl-C: the trainer acts after the reply; a second one: await throws.
        await(POLLIN, wait);
        continue;
      }
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return false;
      if (direct) {
        done += static_cast<size_t>(n);
        continue;
      }
      buffer_start_ = 0;
      buffer_end_ = static_cast<size_t>(n);
    }
    const size_t n = std::min(data.size() - done, buffer_end_ - buffer_start_);
    std::memcpy(data.data() + done, buffer_.data() + buffer_start_, n);
    buffer_start_ += n;
    done += n;
  }
  return true;
}

bool PythonWorker::wait_for_exit(double seconds) {
  if (reaped_) return true;
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (true) {
    const pid_t r = waitpid(pid_, &status_, WNOHANG);
    if (r == pid_ || (r < 0 && errno == ECHILD)) {
      reaped_ = true;
      return true;
    }
    if (std::chrono::steady_clock::now() >= until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

std::string PythonWorker::how_it_ended() {
  if (in_process_) return "(a thread of this process serving a live env object) closed its socket";
  if (pid_ <= 0) return "was not started";
  if (!wait_for_exit(3.0)) {
    kill(pid_, SIGKILL);
    wait_for_exit(10.0);
    return "closed its socket but kept running (killed)";
  }
  if (WIFSIGNALED(status_)) {
    const int sig = WTERMSIG(status_);
    return "was killed by signal " + std::to_string(sig) + " (" + strsignal(sig) + ")";
  }
  if (WIFEXITED(status_)) return "exited with status " + std::to_string(WEXITSTATUS(status_));
  return "ended";
}

void PythonWorker::stop() {
  if (in_process_ && fd_ >= 0 && request_bytes_ > 0 && !hung_) {
    // The serving thread returns on this request, leaving the env object open: its owner
    // closes it (SB3's model.env.close()).
    std::vector<std::byte> request(request_bytes_, std::byte{0});
    request[0] = static_cast<std::byte>(python_protocol::kClose);
    (void)send(fd_, request.data(), request.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
  }
  if (in_process_ || pid_ <= 0 || reaped_) {
    if (fd_ >= 0) close(fd_);
    fd_ = -1;
    return;
  }
  // Before its handshake the worker is importing or building its env (maybe forever), a hung
  // one reads nothing, and one in a step when Ctrl-C came may never finish it: none would act
  // on a close request.
  const bool graceful = !hung_ && request_bytes_ > 0 && !(awaiting_reply_ && interrupt_requested());
  if (graceful && fd_ >= 0) {
    // Best effort: the worker closes its env (env.close()) and returns.
    std::vector<std::byte> request(request_bytes_, std::byte{0});
    request[0] = static_cast<std::byte>(python_protocol::kClose);
    (void)send(fd_, request.data(), request.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
  }
  if (fd_ >= 0) shutdown(fd_, SHUT_WR);
  if (!graceful || !wait_for_exit(2.0)) {
    kill(pid_, SIGKILL);
    wait_for_exit(10.0);
  }
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
}

}  // namespace rlrun
