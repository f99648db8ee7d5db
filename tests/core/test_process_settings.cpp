// The RLRUN_* variables are read by the programs' entry points alone and handed down as
// ProcessSettings (core/process_settings.hpp, apps/common/process_environment.hpp; issue 42:
// no getenv below apps/).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "core/scoped_process_settings.hpp"
#include "process_environment.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/shipped_data.hpp"
#include "rlrun/nn/dense_kernels.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun;
namespace fs = std::filesystem;

TEST_CASE("process settings: no file under src/ or include/ reads the environment but two",
          "[process_settings]") {
  // The operating system's PATH lookup and SUMO's own ${VAR} substitution (docs/architecture.md,
  // "Process settings") are the only reads left below apps/.
  const std::set<std::string> allowed{"src/rlrun/core/find_executable.cpp",
                                      "src/rlrun/envs/sumo/sumo_xml_guard.cpp"};
  const std::regex call(R"(\b(std::)?(secure_)?getenv\s*\()");
  std::set<std::string> readers;
  int files = 0;
  for (const char* top : {"src", "include"}) {
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(RLRUN_SOURCE_DIR) / top)) {
      if (!entry.is_regular_file()) continue;
      ++files;
      std::ifstream in(entry.path());
      std::stringstream text;
      text << in.rdbuf();
      if (std::regex_search(text.str(), call))
        readers.insert(fs::relative(entry.path(), RLRUN_SOURCE_DIR).string());
    }
  }
  CHECK(files > 400);
  for (const std::string& reader : readers) {
    INFO(reader << " reads the environment: take the value from ProcessSettings instead");
    CHECK(allowed.count(reader) == 1);
  }
}

TEST_CASE("process settings: the environment's values, and the settings handed down",
          "[process_settings]") {
  setenv("RLRUN_FFMPEG", "/opt/ffmpeg/bin/ffmpeg", 1);
  setenv("RLRUN_KERNELS", "baseline", 1);
  setenv("MUJOCO_GL", "egl", 1);
  unsetenv("RLRUN_PYTHON");
  const ProcessSettings read = process_settings_from_environment();
  unsetenv("RLRUN_FFMPEG");
  unsetenv("RLRUN_KERNELS");
  unsetenv("MUJOCO_GL");
  CHECK(read.ffmpeg == "/opt/ffmpeg/bin/ffmpeg");
  CHECK(read.kernels == "baseline");
  CHECK(read.mujoco_gl == "egl");
  CHECK(read.python.empty());

  // What the layers below see is what was handed down, not the environment.
  testing::TempDir dir("process_settings");
  fs::create_directories(dir / "data/scenarios");
  setenv("RLRUN_DATA_DIR", "/nonexistent", 1);
  {
    test::ScopedProcessSettings scope([&](ProcessSettings& s) { s.data_dir = dir / "data"; });
    CHECK(fs::path(shipped_data_dir()) == fs::absolute(dir / "data"));
  }
  unsetenv("RLRUN_DATA_DIR");
  CHECK(fs::path(shipped_data_dir()) != fs::absolute(dir / "data"));
}

TEST_CASE("process settings: a kernel path that is not one is refused", "[process_settings]") {
  CHECK_THROWS_WITH(dense::select_kernels("sse9"),
                    Catch::Contains("sse9: expected auto, avx512, avx2 or baseline"));
  dense::select_kernels("baseline");
  CHECK(&dense::active_kernels() == &dense::kernels(dense::KernelPath::kBaseline));
  dense::select_kernels("auto");
  CHECK(&dense::active_kernels() == &dense::kernels(dense::best_kernel_path()));
}
