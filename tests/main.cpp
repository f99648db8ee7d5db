// Catch2 v2 entry point (Debian 12 ships Catch2 2.13). Like rlrun's main(), it reads the RLRUN_*
// environment variables once (apps/common/process_environment.hpp): tests run as a user's
// process would, e.g. RLRUN_KERNELS=baseline build/tests/rlrun_tests.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>
#include <cstdio>
#include <stdexcept>

#include "process_environment.hpp"

int main(int argc, char* argv[]) {
  try {
    rlrun::apply_process_environment();
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "error: RLRUN_KERNELS=%s\n", e.what());
    return 2;
  }
  return Catch::Session().run(argc, argv);
}
