// A tripwire for the plugin binary interface: compiled plugins depend on every declaration
// under include/rlrun/. This test fingerprints those headers (comments and whitespace
// ignored) and fails when they change while RLRUN_PLUGIN_API_VERSION does not, so an
// interface change cannot ship with the old version number and crash old plugins.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "rlrun/version.hpp"
#include "test_paths.hpp"

namespace fs = std::filesystem;

namespace {

// The headers' code without comments or whitespace, files in path order.
std::string normalised_api_text() {
  const fs::path root = fs::path(RLRUN_SOURCE_DIR) / "include";
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(root))
    // rlrun/policy.hpp is the deployment library's API (rlrun::policy), which plugins never
    // see: it changes without a plugin version bump.
    if (entry.is_regular_file() && entry.path().extension() == ".hpp" &&
        entry.path().filename() != "policy.hpp")
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::string text;
  for (const auto& file : files) {
    text += fs::relative(file, root).generic_string() + ":";
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
      const auto comment = line.find("//");
      if (comment != std::string::npos) line.erase(comment);
      for (char c : line)
        if (!std::isspace(static_cast<unsigned char>(c))) text += c;
    }
  }
  return text;
}

uint64_t fnv1a(const std::string& text) {
  uint64_t h = 14695981039346656037ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

TEST_CASE("plugin API: header changes come with a version bump", "[plugin]") {
  // Update BOTH when include/rlrun/ changes: bump RLRUN_PLUGIN_API_VERSION
  // (include/rlrun/version.hpp) if the change can alter the binary interface, then set
  // the fingerprint to the value this test prints.
  constexpr uint32_t kRecordedVersion = 3;
  constexpr uint64_t kRecordedFingerprint =
      0x458947bf9fcac71aull;  // issue 44: Box dtype (float32 | uint8), Tensor DType uint8
  const uint64_t fingerprint = fnv1a(normalised_api_text());
  INFO("include/rlrun/ fingerprint is now 0x"
       << std::hex << fingerprint
       << ": bump RLRUN_PLUGIN_API_VERSION if the binary interface changed, then record "
          "both in tests/runtime/test_plugin_api.cpp");
  CHECK(RLRUN_PLUGIN_API_VERSION == kRecordedVersion);
  CHECK(fingerprint == kRecordedFingerprint);
}
