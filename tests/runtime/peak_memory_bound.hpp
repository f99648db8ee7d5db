#pragma once
// Bounds on a child process's peak resident memory (CommandResult::peak_rss_kb) that hold in
// every build of the tests: under AddressSanitizer (scripts/test_sanitize.sh) rlrun keeps
// shadow memory and quarantined blocks besides its own, about twice as much again, so the
// bound is tripled there. It still tells a bounded read (tens of MB) from the gigabytes a
// crafted file would need if read or inflated whole.

namespace rlrun::testing {

constexpr long peak_rss_bound_kb(long release_build_kb) {
#if defined(__SANITIZE_ADDRESS__)
  return 3 * release_build_kb;
#else
  return release_build_kb;
#endif
}

}  // namespace rlrun::testing
