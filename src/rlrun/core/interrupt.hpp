#pragma once
// Ctrl-C (SIGINT) and SIGTERM as a request, not a kill: the first asks the running command to
// stop at its next safe point (training writes a checkpoint there, recording closes its video),
// the second to stop at once. Long-running parts poll these functions; nothing is done inside
// the signal handler but counting, reading the clock and one async-signal-safe write(2).
//
// Before a command installs the handlers (while it reads its files, builds and checks envs),
// SIGINT and SIGTERM end rlrun as they end any program (a worker dies with it: PR_SET_PDEATHSIG,
// core/worker_spawn.hpp). A third interrupt ends rlrun at once whatever it is doing: the last
// resort where a wait cannot be interrupted (a call into SUMO's TraCI client library).
#include <chrono>
#include <string>

namespace rlrun {

// SIGINT and SIGTERM to their default action, also when rlrun's parent ignored SIGINT (a
// non-interactive shell starts background jobs so): main() calls it first, so that Ctrl-C and
// `kill -INT` stop rlrun in every phase.
void use_default_interrupt_actions();
// Installs the handlers (idempotent).
void install_interrupt_handlers();
// At least one SIGINT/SIGTERM since the handlers were installed.
bool interrupt_requested();
// How many arrived (2 or more: stop now).
int interrupt_count();
// The first one's signal (SIGINT or SIGTERM; 0 before any) and when it arrived.
int interrupt_signal();
std::chrono::steady_clock::time_point interrupt_time();
// "Ctrl-C" or "SIGTERM": the first interrupt, for messages.
std::string interrupt_name();
// Forgets the interrupts counted so far: a process that runs one command after another (the
// Python package's rlrun.train, python/) starts each with none.
void clear_interrupts();

}  // namespace rlrun
