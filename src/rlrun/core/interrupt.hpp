#pragma once
// Ctrl-C (SIGINT) and SIGTERM as a request, not a kill: the first asks the running command to
// stop at its next safe point (training writes a checkpoint there, recording closes its video),
// the second to stop at once. Long-running parts poll these functions; nothing is done inside
// the signal handler but counting and one async-signal-safe write(2).
namespace rlrun {

// Installs the handlers (idempotent).
void install_interrupt_handlers();
// At least one SIGINT/SIGTERM since the handlers were installed.
bool interrupt_requested();
// How many arrived (2 or more: stop now).
int interrupt_count();
// Forgets the interrupts counted so far: a process that runs one command after another (the
// Python package's rlrun.train, python/) starts each with none.
void clear_interrupts();

}  // namespace rlrun
