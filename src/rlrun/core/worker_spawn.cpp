#include "rlrun/core/worker_spawn.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>

#include "rlrun/core/errors.hpp"

namespace rlrun {

SpawnedWorker spawn_worker(std::vector<std::string> args, int child_fd, const std::string& what) {
  struct sigaction current;
  if (sigaction(SIGPIPE, nullptr, &current) == 0 && current.sa_handler == SIG_DFL)
    std::signal(SIGPIPE, SIG_IGN);
  int fds[2];
  if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds) != 0)
    throw RuntimeFailure("cannot create a socket for " + what + ": " + std::strerror(errno));
  const int null_fd = open("/dev/null", O_RDONLY | O_CLOEXEC);
  // Everything the child needs is made before fork().
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    const int error = errno;
    close(fds[0]);
    close(fds[1]);
    if (null_fd >= 0) close(null_fd);
    throw RuntimeFailure("cannot start " + what + " (fork): " + std::strerror(error));
  }
  if (pid == 0) {
    prctl(PR_SET_PDEATHSIG, SIGKILL);   // dies with rlrun, whatever kills rlrun
    if (getppid() != parent) _exit(1);  // rlrun died before the line above
    signal(SIGINT, SIG_IGN);            // kept across exec
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    if (null_fd >= 0) dup2(null_fd, STDIN_FILENO);
    if (fds[1] == child_fd)
      fcntl(child_fd, F_SETFD, 0);  // keep it across exec
    else
      dup2(fds[1], child_fd);  // the copy is not close-on-exec
    execv(argv[0], argv.data());
    _exit(127);
  }
  close(fds[1]);
  if (null_fd >= 0) close(null_fd);
  return {pid, fds[0]};
}

}  // namespace rlrun
