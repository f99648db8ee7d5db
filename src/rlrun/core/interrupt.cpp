#include "rlrun/core/interrupt.hpp"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <ctime>

namespace rlrun {

namespace {

std::atomic<int> g_interrupts{0};
std::atomic<int> g_signal{0};
std::atomic<long long> g_time_ns{0};  // CLOCK_MONOTONIC, steady_clock's clock on Linux

void say(const char* text, size_t size) {
  // write(2) is async-signal-safe; iostreams are not.
  const ssize_t ignored = write(STDERR_FILENO, text, size);
  (void)ignored;
}

void on_signal(int sig) {
  static const char first[] =
      "\nrlrun: stopping at the next safe point to write a checkpoint "
      "(Ctrl-C again stops at once, without one)\n";
  static const char third[] = "\nrlrun: stopping now (a third interrupt)\n";
  if (g_interrupts.load() == 0) {  // when and which, before the count says there is one
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);  // async-signal-safe (POSIX.1-2008)
    g_time_ns.store(static_cast<long long>(now.tv_sec) * 1000000000LL + now.tv_nsec);
    g_signal.store(sig);
  }
  const int before = g_interrupts.fetch_add(1);
  if (before == 0) {
    say(first, sizeof first - 1);
  } else if (before >= 2) {
    say(third, sizeof third - 1);
    // Ends rlrun as the signal would without a handler (blocked until the handler returns).
    std::signal(sig, SIG_DFL);
    raise(sig);
  }
}

}  // namespace

void use_default_interrupt_actions() {
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
}

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  // Restarted system calls, as std::signal's: what polls the count wakes up by poll(2)'s EINTR
  // (never restarted) or its own timeout.
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool interrupt_requested() { return g_interrupts.load() > 0; }
int interrupt_count() { return g_interrupts.load(); }
int interrupt_signal() { return g_signal.load(); }

std::chrono::steady_clock::time_point interrupt_time() {
  return std::chrono::steady_clock::time_point(std::chrono::nanoseconds(g_time_ns.load()));
}

std::string interrupt_name() { return g_signal.load() == SIGTERM ? "SIGTERM" : "Ctrl-C"; }

void clear_interrupts() {
  g_interrupts.store(0);
  g_signal.store(0);
  g_time_ns.store(0);
}

}  // namespace rlrun
