#pragma once
// A shared library whose constructor runs as it is loaded (dlopen) and leaves a marker file.
// Security tests name it wherever untrusted text could make rlrun load a plugin, and check that
// the marker never appears (docs/security.md).
#include <catch2/catch.hpp>
#include <fstream>
#include <string>

#include "runtime/cli_runner.hpp"

namespace rlrun::testing {

// Builds DIR/libevil.so with the system's C compiler, writing `marker` when loaded; its path.
inline std::string build_marker_library(const TempDir& dir, const std::string& marker) {
  std::ofstream(dir / "evil.c") << "#include <stdio.h>\n"
                                   "__attribute__((constructor)) static void f(void) { FILE* f = "
                                   "fopen(\""
                                << marker << "\", \"w\"); if (f) fclose(f); }\n";
  const std::string library = dir / "libevil.so";
  REQUIRE(run_command("cc -shared -fPIC -o " + library + " " + dir / "evil.c").exit_code == 0);
  return library;
}

}  // namespace rlrun::testing
