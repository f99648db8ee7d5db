// Every relative link in the README and the guides leads to a file of this checkout, and every
// `#anchor` to a heading of its page (issue 41: the README linked a file outside the repo).
// Anchors follow GitHub's rule for heading ids: lower case, punctuation other than '-' and '_'
// dropped, spaces as '-'.
#include <catch2/catch.hpp>

#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

std::string github_anchor(const std::string& heading) {
  std::string id;
  for (std::size_t i = 0; i < heading.size(); ++i) {
    const auto u = static_cast<unsigned char>(heading[i]);
    // U+2000-U+206F (dashes, quotes, ...) are punctuation: their UTF-8 is E2 80-81 xx.
    if (u == 0xe2 && i + 2 < heading.size() &&
        (static_cast<unsigned char>(heading[i + 1]) & 0xfe) == 0x80) {
      i += 2;
      continue;
    }
    if (std::isalnum(u) || u == '-' || u == '_' || u >= 0x80)
      id += static_cast<char>(std::tolower(u));
    else if (u == ' ')
      id += '-';
  }
  return id;
}

// The ids of a markdown page's headings (outside fenced code blocks).
std::set<std::string> anchors_of(const std::string& text) {
  std::set<std::string> ids;
  bool in_code = false;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    const std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    if (line.rfind("```", 0) == 0) in_code = !in_code;
    if (in_code || line.empty() || line[0] != '#') continue;
    const std::size_t title = line.find_first_not_of('#');
    if (title == std::string::npos || line[title] != ' ') continue;
    ids.insert(github_anchor(line.substr(title + 1)));
  }
  return ids;
}

std::vector<fs::path> pages() {
  const fs::path root = RLRUN_SOURCE_DIR;
  std::vector<fs::path> out{root / "README.md"};
  for (const auto& dir : {root / "docs", root / "examples"})
    for (const auto& entry : fs::recursive_directory_iterator(dir))
      if (entry.path().extension() == ".md") out.push_back(entry.path());
  return out;
}

}  // namespace

TEST_CASE("docs: every relative link leads to a file of the checkout and an existing heading",
          "[docs]") {
  const fs::path root = fs::canonical(RLRUN_SOURCE_DIR);
  const std::regex link(R"(\]\(([^)\s]+)\))");
  int checked = 0;
  for (const fs::path& page : pages()) {
    const std::string text = read_text(page.string());
    INFO(page.string());
    CHECK(text.find(std::string("../") + "shared") == std::string::npos);  // beside a checkout
    for (std::sregex_iterator it(text.begin(), text.end(), link), end; it != end; ++it) {
      const std::string target = (*it)[1].str();
      if (target.rfind("http://", 0) == 0 || target.rfind("https://", 0) == 0 ||
          target.rfind("mailto:", 0) == 0)
        continue;
      INFO(page.string() << ": " << target);
      const std::size_t hash = target.find('#');
      const std::string file_part = target.substr(0, hash);
      const fs::path file = file_part.empty() ? page : page.parent_path() / file_part;
      REQUIRE(fs::exists(file));
      const fs::path resolved = fs::canonical(file);
      CHECK(std::mismatch(root.begin(), root.end(), resolved.begin(), resolved.end()).first ==
            root.end());
      if (hash != std::string::npos && resolved.extension() == ".md")
        CHECK(anchors_of(read_text(resolved.string())).count(target.substr(hash + 1)) == 1);
      ++checked;
    }
  }
  CHECK(checked > 50);
}

TEST_CASE("repo: no file refers to material outside the checkout", "[docs]") {
  // The reading material beside a developer's checkout (its design notes and reference data) is
  // not part of the repo: what the project needs of it lives in docs/ and tests/data/.
  const std::vector<std::string> outside{std::string("../") + "shared",
                                         std::string("DESIGN") + ".md"};
  const fs::path root = RLRUN_SOURCE_DIR;
  int scanned = 0;
  for (const char* file : {"README.md", "CMakeLists.txt"}) {
    const std::string text = read_text((root / file).string());
    for (const std::string& name : outside) {
      INFO(file << " mentions " << name);
      CHECK(text.find(name) == std::string::npos);
    }
  }
  for (const char* dir : {"src", "include", "apps", "python", "tests", "scripts", "fuzz", "docs",
                          "examples", "configs", ".ci"}) {
    if (!fs::exists(root / dir)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root / dir)) {
      if (!entry.is_regular_file() || entry.file_size() > (1 << 20)) continue;
      const std::string text = read_text(entry.path().string());
      for (const std::string& name : outside) {
        INFO(entry.path().string() << " mentions " << name);
        CHECK(text.find(name) == std::string::npos);
      }
      ++scanned;
    }
  }
  CHECK(scanned > 500);
}

// scripts/ is grouped by purpose (scripts/README.md): every scripts/<path> that a page, a
// script, a test or a build file names must be there, so a script moved between groups cannot
// leave a stale command behind.
TEST_CASE("every scripts/ path named in the repo exists", "[docs]") {
  const fs::path root = rlrun::test_paths::source_dir();
  const std::regex named(R"((?:^|[^A-Za-z0-9_./-])(scripts/[A-Za-z0-9_./-]*[A-Za-z0-9_]))");
  int checked = 0;
  for (const char* dir : {"README.md", "CMakeLists.txt", ".ci", "apps", "bench", "configs", "docs",
                          "examples", "fuzz", "python", "scripts", "src", "tests"}) {
    if (!fs::exists(root / dir)) continue;
    std::vector<fs::path> files;
    if (fs::is_regular_file(root / dir))
      files.push_back(root / dir);
    else
      for (const auto& entry : fs::recursive_directory_iterator(root / dir))
        if (entry.is_regular_file() && entry.file_size() < (1 << 20)) files.push_back(entry.path());
    for (const fs::path& file : files) {
      const std::string text = read_text(file.string());
      for (std::sregex_iterator m(text.begin(), text.end(), named), end; m != end; ++m) {
        const std::string path = (*m)[1].str();
        if (path.find("...") != std::string::npos) continue;
        INFO(file.string() << " names " << path);
        CHECK(fs::exists(root / path));
        ++checked;
      }
    }
  }
  CHECK(checked > 50);
}
