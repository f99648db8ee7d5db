// The table of ready-made experiment files (docs/configs.md, linked from the README) names every
// file in configs/ (issue 18: the list once left out grasp_sac and grasp_easy_sac), and names no
// file that is not there.
#include <catch2/catch.hpp>

#include <filesystem>
#include <regex>
#include <set>

#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun::testing;
namespace fs = std::filesystem;

TEST_CASE("docs/configs.md lists every config in configs/", "[docs]") {
  const std::string page = read_text(std::string(RLRUN_SOURCE_DIR) + "/docs/configs.md");
  // The table that starts with the header "| file |" and ends at the next blank line.
  const size_t start = page.find("| file |");
  REQUIRE(start != std::string::npos);
  const std::string list = page.substr(start, page.find("\n\n", start) - start);
  std::set<std::string> on_disk;
  for (const auto& entry : fs::directory_iterator(std::string(RLRUN_SOURCE_DIR) + "/configs"))
    if (entry.path().extension() == ".yaml") on_disk.insert(entry.path().stem().string());
  REQUIRE(on_disk.size() >= 19);
  for (const std::string& name : on_disk) {
    INFO(name);
    CHECK(list.find("`" + name + "`") != std::string::npos);
  }
  const std::regex named("`([a-z0-9_]+)`");
  for (std::sregex_iterator it(list.begin(), list.end(), named), end; it != end; ++it) {
    INFO((*it)[1].str());
    CHECK(on_disk.count((*it)[1].str()) == 1);
  }
}
