// core/zip_reader.hpp on hostile archives written by the test (core/crafted_zip.hpp).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/crafted_zip.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/zip_archive.hpp"
#include "rlrun/core/zip_reader.hpp"
#include "runtime/cli_runner.hpp"

using namespace rlrun;
using namespace rlrun::testing;

namespace {

std::string open_error(const std::string& path) {
  try {
    ZipReader reader(path);
  } catch (const RuntimeFailure& e) {
    return e.what();
  }
  return "";
}

// Reads every member with ZipReader::read (limit: `max_bytes`); the error, or "".
std::string read_error(const std::string& path, uint64_t max_bytes = 1 << 20) {
  try {
    const ZipReader reader(path);
    for (const ZipEntry& e : reader.entries()) reader.read(e, max_bytes);
  } catch (const RuntimeFailure& e) {
    return e.what();
  }
  return "";
}

CraftedMember plain(const std::string& name, const std::string& text) {
  return CraftedMember{name, bytes_of(text)};
}

}  // namespace

TEST_CASE("zip reader: member names that could escape a directory are refused", "[core][zip]") {
  TempDir dir("zip_names");
  const std::string path = dir / "m.zip";
  const auto refused = [&](const std::string& name, const std::string& reason) {
    write_crafted_zip(path, {plain("meta.json", "{}"), plain(name, "x")});
    const std::string error = open_error(path);
    INFO(error);
    CHECK(error.find(path + ": member '") == 0);
    CHECK(error.find(reason) != std::string::npos);
  };
  refused("../evil.npy", "a '..' component");
  refused("training/../../evil.npy", "a '..' component");
  refused("a/..", "a '..' component");
  refused("/etc/passwd", "an absolute path");
  refused("a\\b.npy", "a backslash");
  // libzip passes names on as stored (\t, \r, \n, UTF-8) or converts them from CP437
  // (other control bytes become printable characters): a newline is what can arrive.
  refused("a\nerror: fake.npy", "a control character");
  refused("a\tb.npy", "a control character");
  refused(std::string(600, 'a') + ".npy", "longer than 512 bytes");
  // The name is shown with control bytes escaped (no terminal escapes in messages).
  write_crafted_zip(path, {plain("x\nerror: fake.npy", "x")});
  CHECK(open_error(path).find("member 'x\\x0aerror: fake.npy'") != std::string::npos);
  // Names rlrun writes, dots included, are fine.
  write_crafted_zip(path, {plain("wrappers/NormalizeObservation.1/mean.npy", "x"),
                           plain("training/..hidden/x.npy", "y"), plain("dir/", "")});
  CHECK(open_error(path).empty());
}

TEST_CASE("zip reader: a member name twice is refused", "[core][zip]") {
  TempDir dir("zip_duplicate");
  const std::string path = dir / "m.zip";
  write_crafted_zip(path, {plain("a.npy", "1"), plain("b.npy", "2")});
  // libzip will not write a name twice: rename b.npy to a.npy in both headers.
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  for (size_t at = bytes.find("b.npy"); at != std::string::npos; at = bytes.find("b.npy", at))
    bytes[at] = 'a';
  std::ofstream(path, std::ios::binary) << bytes;
  CHECK(open_error(path).find("member 'a.npy' appears twice") != std::string::npos);
}

TEST_CASE("zip reader: declared sizes are claims, checked before and while reading",
          "[core][zip]") {
  TempDir dir("zip_sizes");
  const std::string path = dir / "m.zip";
  // 4 GiB declared, 16 bytes inside: refused from the declaration, nothing allocated.
  CraftedMember liar{"w.npy", raw_deflate(std::vector<uint8_t>(16, 7))};
  liar.raw = true;
  liar.declared_size = uint64_t{4} << 30;
  write_crafted_zip(path, {liar});
  CHECK(std::filesystem::file_size(path) < 1000);
  CHECK(read_error(path).find("member 'w.npy' declares 4294967296 bytes, more than the 1048576 "
                              "allowed") != std::string::npos);
  CHECK_THROWS_WITH(read_zip(path, 1 << 20),
                    Catch::Contains("members declare 4294967296 bytes, more than the 1048576"));

  // Fewer bytes than declared.
  liar.declared_size = 100;
  write_crafted_zip(path, {liar});
  std::string error = read_error(path);
  INFO(error);
  CHECK(error.find(path + ": member 'w.npy' ") == 0);
  CHECK((error.find("ends after 16 of its declared 100 bytes") != std::string::npos ||
         error.find("is corrupt") != std::string::npos));

  // A bomb: declares 100 bytes, inflates to 1 GiB of zeros; reading stops after 101 bytes.
  CraftedMember bomb{"w.npy", {}};
  bomb.raw = true;
  bomb.data = deflate_bomb({}, uint64_t{1} << 30, bomb.crc);
  bomb.declared_size = 100;
  write_crafted_zip(path, {bomb});
  CHECK(std::filesystem::file_size(path) < (2u << 20));
  CHECK(read_error(path).find("member 'w.npy' holds more data than its declared 100 bytes") !=
        std::string::npos);
  // The same bomb declaring its true size is refused by the limit before any inflating.
  bomb.declared_size = uint64_t{1} << 30;
  write_crafted_zip(path, {bomb});
  CHECK(read_error(path).find("declares 1073741824 bytes") != std::string::npos);
}

TEST_CASE("zip reader: corrupt data names the member (no use after zip_close)", "[core][zip]") {
  TempDir dir("zip_corrupt");
  const std::string path = dir / "m.zip";
  // Block type 3 is invalid deflate (RFC 1951 3.2.3).
  CraftedMember corrupt{"policy.weight.npy", std::vector<uint8_t>(64, 0xff)};
  corrupt.raw = true;
  corrupt.declared_size = 4096;
  write_crafted_zip(path, {plain("meta.json", "{}"), corrupt});
  std::string error = read_error(path);
  INFO(error);
  CHECK(error.find(path + ": member 'policy.weight.npy' is corrupt (") == 0);

  // A wrong CRC: the data inflates to its declared size but is not what was stored.
  const std::vector<uint8_t> data(100, 42);
  CraftedMember wrong_crc{"w.npy", raw_deflate(data)};
  wrong_crc.raw = true;
  wrong_crc.declared_size = data.size();
  wrong_crc.crc = 12345;
  write_crafted_zip(path, {wrong_crc});
  error = read_error(path);
  INFO(error);
  CHECK(error.find("member 'w.npy' is corrupt (CRC error)") != std::string::npos);
  // With the right CRC the same member reads back.
  wrong_crc.crc = static_cast<uint32_t>(crc32(0, data.data(), static_cast<uInt>(data.size())));
  write_crafted_zip(path, {wrong_crc});
  CHECK(read_error(path).empty());
  CHECK(read_zip(path).at("w.npy") == data);
}

TEST_CASE("zip reader: at most 65536 members", "[core][zip]") {
  TempDir dir("zip_count");
  const std::string path = dir / "m.zip";
  std::vector<CraftedMember> members;
  for (size_t i = 0; i <= kMaxZipMembers; ++i) members.push_back(plain(std::to_string(i), ""));
  for (auto& m : members) m.deflate = false;
  write_crafted_zip(path, members);
  CHECK(open_error(path).find("holds 65537 members, more than the 65536") != std::string::npos);
}

TEST_CASE("zip reader: missing and non-zip files", "[core][zip]") {
  TempDir dir("zip_missing");
  CHECK(open_error(dir / "none.zip") == dir / "none.zip" + ": no such file");
  CHECK(open_error(dir.str()) == dir.str() + ": not a regular file");
  std::ofstream(dir / "junk.zip") << "not a zip";
  CHECK(open_error(dir / "junk.zip").find("not a readable model file") != std::string::npos);
}
