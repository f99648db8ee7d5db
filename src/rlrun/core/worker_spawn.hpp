#pragma once
// Starting a worker program that talks to rlrun over a socket (the Python env worker, the SUMO
// worker): fork + exec, never a bare fork (another thread of rlrun may hold the allocator's
// lock, so the child only makes system calls until exec).
#include <sys/types.h>

#include <string>
#include <vector>

namespace rlrun {

struct SpawnedWorker {
  pid_t pid = -1;
  int fd = -1;  // rlrun's end of the socket pair
};

// Runs `argv` (argv[0] the program's path) with the other end of a Unix stream socket pair as
// file descriptor `child_fd`, stdin from /dev/null, every signal unblocked and SIGINT ignored
// (rlrun handles Ctrl-C), dying with rlrun (PR_SET_PDEATHSIG: `kill -9`, a crash). rlrun ignores
// SIGPIPE from then on, so a worker that has gone is an error, not the end of rlrun. A program
// that cannot be executed exits with status 127. Throws RuntimeFailure naming `what` when the
// socket or the process cannot be made.
SpawnedWorker spawn_worker(std::vector<std::string> argv, int child_fd, const std::string& what);

}  // namespace rlrun
