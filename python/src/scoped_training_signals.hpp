#pragma once
// While rlrun trains from Python (rlrun.train, model.learn), rlrun's own SIGINT/SIGTERM handlers
// (core/interrupt.hpp) replace Python's, so Ctrl-C stops training as on the command line: at the
// next safe point. Python's handlers come back when training ends however it ends.
#include <csignal>

#include "rlrun/core/interrupt.hpp"

namespace rlrun::python {

class ScopedTrainingSignals {
 public:
  ScopedTrainingSignals() {
    sigaction(SIGINT, nullptr, &old_int_);
    sigaction(SIGTERM, nullptr, &old_term_);
    clear_interrupts();
    install_interrupt_handlers();
  }
  ~ScopedTrainingSignals() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
    // The outcome has been taken: a later wait (rlrun.make's worker) must not see this Ctrl-C.
    clear_interrupts();
  }
  ScopedTrainingSignals(const ScopedTrainingSignals&) = delete;
  ScopedTrainingSignals& operator=(const ScopedTrainingSignals&) = delete;

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

}  // namespace rlrun::python
