#include "rlrun/core/interrupt.hpp"

#include <unistd.h>

#include <atomic>
#include <csignal>

namespace rlrun {

namespace {

std::atomic<int> g_interrupts{0};

void on_signal(int) {
  // write(2) is async-signal-safe; iostreams are not.
  static const char first[] =
      "\nrlrun: stopping at the next safe point to write a checkpoint "
      "(Ctrl-C again stops at once, without one)\n";
  if (g_interrupts.fetch_add(1) == 0) {
    const ssize_t ignored = write(STDERR_FILENO, first, sizeof first - 1);
    (void)ignored;
  }
}

}  // namespace

void install_interrupt_handlers() {
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}

bool interrupt_requested() { return g_interrupts.load() > 0; }
int interrupt_count() { return g_interrupts.load(); }
void clear_interrupts() { g_interrupts.store(0); }

}  // namespace rlrun
