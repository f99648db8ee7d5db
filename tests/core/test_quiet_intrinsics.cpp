// src/rlrun/core/quiet_intrinsics.hpp: GCC's warnings inside its own AVX-512 intrinsics header
// are silenced, a maybe-uninitialized read in our own code is still reported. Compiles small
// files with the project's compiler and flags (-O2 -Wall -Wextra -march=native).
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <string>

#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using rlrun::testing::run_command;
using rlrun::testing::TempDir;

namespace {

std::string compile(const TempDir& dir, const std::string& name, const std::string& code,
                    bool quiet_header) {
  const std::string file = dir / (name + ".cpp");
  std::ofstream(file) << code;
  std::string cmd = std::string(RLRUN_CXX_COMPILER) +
                    " -std=c++20 -O2 -Wall -Wextra -march=native -isystem /usr/include/eigen3";
  if (quiet_header)
    cmd += std::string(" -include ") + RLRUN_SOURCE_DIR + "/src/rlrun/core/quiet_intrinsics.hpp";
  return run_command(cmd + " -c " + file + " -o " + (dir / (name + ".o"))).output;
}

}  // namespace

TEST_CASE("quiet intrinsics: our own maybe-uninitialized reads are still reported", "[core]") {
  if (std::string(RLRUN_CXX_COMPILER_ID) != "GNU") {
    WARN("not GCC: quiet_intrinsics.hpp is not used");
    return;
  }
  TempDir dir("quiet_intrinsics_own");
  const std::string out = compile(dir, "own",
                                  "int g(int);\n"
                                  "int f(int c) { int x; if (c) x = g(1); g(2); return x; }\n",
                                  true);
  CHECK_THAT(out, Catch::Contains("uninitialized"));
}

TEST_CASE("quiet intrinsics: Eigen's vector code compiles without warnings from GCC's headers",
          "[core]") {
  if (std::string(RLRUN_CXX_COMPILER_ID) != "GNU") {
    WARN("not GCC: quiet_intrinsics.hpp is not used");
    return;
  }
  TempDir dir("quiet_intrinsics_eigen");
  // The pattern that warns on AVX-512 machines with GCC 12: Eigen's packet math on float
  // matrices (as nn/orthogonal_init.cpp's QR decomposition).
  const std::string code =
      "#include <Eigen/Dense>\n"
      "Eigen::MatrixXf q(const Eigen::MatrixXf& a) { return "
      "Eigen::HouseholderQR<Eigen::MatrixXf>(a).householderQ(); }\n"
      "float s(const Eigen::MatrixXf& a, const Eigen::MatrixXf& b) { return (a * "
      "b).array().tanh().sum(); }\n";
  const std::string without = compile(dir, "eigen_plain", code, false);
  const std::string with = compile(dir, "eigen_quiet", code, true);
  // Where GCC warns at all (AVX-512 machines), the header removes every one.
  WARN("without the header: " << std::count(without.begin(), without.end(), '\n')
                              << " lines of compiler output");
  CHECK(with.find("warning:") == std::string::npos);
}
