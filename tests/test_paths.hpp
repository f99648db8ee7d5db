#pragma once
// Paths of this checkout and of its build, for tests that read shipped files or start the
// rlrun binary. They live in one file CMake generates (build/generated/test_paths.cpp, from
// tests/CMakeLists.txt), not in compile definitions on every test source: a test object then
// does not depend on where the checkout is, so two checkouts (git worktrees) share compiled
// tests through a compiler cache, and changing a path rebuilds one file.

namespace rlrun::test_paths {
const char* source_dir();     // the checkout (configs/, scenarios/, tests/data/, ...)
const char* rlrun_binary();   // build/rlrun
const char* gym_reference();  // tests/data/gymnasium (tests/envs/test_gym_reference.cpp)
const char* node_modules();   // onnxruntime-node for the ONNX export tests (scripts/setup.sh)
const char* cxx_compiler();   // the compiler this build uses (tests/core/test_quiet_intrinsics.cpp)
const char* cxx_compiler_id();  // CMake's name for it: GNU, Clang
const char* policy_library();   // build/librlrun_policy.so (the deploy library, docs/deploy.md)
}  // namespace rlrun::test_paths

#define RLRUN_SOURCE_DIR (::rlrun::test_paths::source_dir())
#define RLRUN_BINARY (::rlrun::test_paths::rlrun_binary())
#define RLRUN_DEFAULT_GYM_REFERENCE (::rlrun::test_paths::gym_reference())
#define RLRUN_TEST_NODE_MODULES (::rlrun::test_paths::node_modules())
#define RLRUN_CXX_COMPILER (::rlrun::test_paths::cxx_compiler())
#define RLRUN_CXX_COMPILER_ID (::rlrun::test_paths::cxx_compiler_id())
#define RLRUN_POLICY_LIBRARY (::rlrun::test_paths::policy_library())
