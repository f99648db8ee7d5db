// core/dir_handle, core/regular_file and core/line_reader: how rlrun opens the files of run
// directories and studies (issue 41, item 4). Links are refused, never followed; only regular
// files are read or written; the open never blocks; reads stop at their bound.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "rlrun/core/dir_handle.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/line_reader.hpp"
#include "rlrun/core/regular_file.hpp"
#include "runtime/cli_runner.hpp"

using namespace rlrun;
using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

void write_file(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

}  // namespace

TEST_CASE("DirHandle: links are refused, not followed, the user's path above is",
          "[core][security]") {
  TempDir tmp("dir_handle_links");
  fs::create_directories(tmp / "real/run/checkpoints");
  fs::create_directories(tmp / "elsewhere");
  write_file(tmp / "victim.txt", "keep\n");
  fs::create_symlink(tmp / "real", tmp / "user_link");             // the user's own link
  fs::create_symlink(tmp / "real/run", tmp / "run_link");          // a link to a run
  fs::create_symlink(tmp / "elsewhere", tmp / "real/run/videos");  // planted inside
  fs::create_symlink(tmp / "victim.txt", tmp / "real/run/log.txt");

  const DirHandle run = DirHandle::open(tmp / "user_link/run/");  // through the user's link
  CHECK(run.path() == tmp / "user_link/run");
  CHECK_THROWS_WITH(DirHandle::open(tmp / "run_link"),
                    Catch::Contains("run_link is a symbolic link"));
  CHECK_THROWS_WITH(DirHandle::open(tmp / "run_link/"), Catch::Contains("is a symbolic link"));
  CHECK(DirHandle::open(tmp / "run_link", DirHandle::LastLink::kFollow).is_open());
  CHECK_THROWS_WITH(DirHandle::open(tmp / "nowhere"), Catch::Contains("no such directory"));

  CHECK(run.kind("log.txt") == EntryKind::kSymlink);
  CHECK(run.kind("checkpoints") == EntryKind::kDirectory);
  CHECK(run.kind("missing") == EntryKind::kMissing);
  CHECK_THROWS_WITH(run.kind("../x"), Catch::Contains("not a plain file name"));
  CHECK(run.subdir("checkpoints"));
  CHECK_FALSE(run.subdir("missing"));
  CHECK_THROWS_WITH(run.make_subdir("videos"), Catch::Contains("/videos is a symbolic link"));
  CHECK_THROWS_WITH(run.open_for_writing("log.txt", CheckedFile::Mode::kAppend),
                    Catch::Contains("log.txt is a symbolic link"));
  CHECK_THROWS_WITH(run.read("log.txt", 100), Catch::Contains("log.txt is a symbolic link"));
  CHECK_THROWS_WITH(CheckedFile::run_file(tmp / "real/run/log.txt", CheckedFile::Mode::kTruncate),
                    Catch::Contains("is a symbolic link"));
  CHECK(read_text(tmp / "victim.txt") == "keep\n");

  // Atomic replacement replaces the link itself; removal removes the link itself.
  run.write_atomic("log.txt", "new\n");
  CHECK(run.kind("log.txt") == EntryKind::kRegular);
  CHECK(read_text(tmp / "victim.txt") == "keep\n");
  CHECK(run.remove("videos"));
  CHECK(fs::exists(tmp / "elsewhere"));
  CHECK_FALSE(run.remove("videos"));

  const auto entries = run.list();
  REQUIRE(entries.size() == 2);
  CHECK(entries[0].name == "checkpoints");
  CHECK(entries[0].kind == EntryKind::kDirectory);
  CHECK(entries[1].name == "log.txt");
  CHECK(entries[1].kind == EntryKind::kRegular);
}

TEST_CASE("DirHandle: FIFOs and devices are refused without blocking", "[core][security]") {
  TempDir tmp("dir_handle_fifo");
  REQUIRE(mkfifo((tmp / "fifo").c_str(), 0600) == 0);
  const DirHandle dir = DirHandle::open(tmp.str());
  CHECK(dir.kind("fifo") == EntryKind::kOther);
  CHECK_THROWS_WITH(dir.read("fifo", 100),
                    Catch::Contains("fifo is a FIFO (named pipe), not a regular file"));
  CHECK_THROWS_WITH(dir.open_for_writing("fifo", CheckedFile::Mode::kAppend),
                    Catch::Contains("is a FIFO (named pipe)"));
  CHECK_THROWS_WITH(dir.write_atomic("fifo", "x"), Catch::Contains("not a regular file"));
  CHECK(fs::is_fifo(tmp / "fifo"));
  CHECK_THROWS_WITH(open_regular_file(AT_FDCWD, "/dev/zero", O_RDONLY, "/dev/zero"),
                    Catch::Contains("/dev/zero is a character device, not a regular file"));
  CHECK_THROWS_WITH(CheckedFile::run_file("/dev/full", CheckedFile::Mode::kAppend),
                    Catch::Contains("is a character device"));
  CHECK_FALSE(open_regular_file(AT_FDCWD, tmp / "missing", O_RDONLY, "missing"));
}

TEST_CASE("DirHandle: reads stop at their bound, a missing file is none", "[core][security]") {
  TempDir tmp("dir_handle_bounds");
  write_file(tmp / "a.csv", "x,y\n1,2\n3,4");
  const DirHandle dir = DirHandle::open(tmp.str());
  CHECK(dir.read("a.csv", 100) == "x,y\n1,2\n3,4");
  CHECK_THROWS_WITH(dir.read("a.csv", 10),
                    Catch::Contains("a.csv is larger than 10 bytes, the most rlrun reads of it"));
  CHECK_FALSE(dir.read("missing", 10));
  CHECK_FALSE(dir.read_lines("missing", 10, 10));

  std::optional<LineReader> lines = dir.read_lines("a.csv", 100, 3);
  std::string line;
  REQUIRE(lines->next(line));
  CHECK(line == "x,y");
  REQUIRE(lines->next(line));
  CHECK(line == "1,2");
  REQUIRE(lines->next(line));  // the last line has no newline: a line still
  CHECK(line == "3,4");
  CHECK_FALSE(lines->next(line));

  write_file(tmp / "long.txt", "short\n" + std::string(100, 'x') + "\nend\n");
  lines = dir.read_lines("long.txt", 1000, 10);
  CHECK(lines->next(line));
  CHECK_THROWS_WITH(lines->next(line), Catch::Contains("long.txt:2: a line longer than 10 bytes"));
  lines = dir.read_lines("long.txt", 1000, 10, LineReader::LongLines::kCut);
  CHECK(lines->next(line));
  CHECK(lines->next(line));
  CHECK(line == std::string(10, 'x'));
  CHECK(lines->next(line));
  CHECK(line == "end");
  lines = dir.read_lines("long.txt", 50, 1000);
  CHECK_THROWS_WITH((lines->next(line), lines->next(line)),
                    Catch::Contains("long.txt is larger than 50 bytes"));
}

TEST_CASE("DirHandle: write_atomic and write_text_atomic keep mode and leave no temporary",
          "[core]") {
  TempDir tmp("dir_handle_atomic");
  const DirHandle dir = DirHandle::open(tmp.str());
  dir.write_atomic("config.yaml", "a: 1\n");
  dir.write_atomic("config.yaml", "a: 2\n");
  CHECK(read_text(tmp / "config.yaml") == "a: 2\n");
  CHECK((fs::status(tmp / "config.yaml").permissions() & fs::perms::others_read) !=
        fs::perms::none);
  const auto entries = dir.list();
  REQUIRE(entries.size() == 1);
  CHECK(entries[0].name == "config.yaml");
  // A subdirectory made, then written into by name.
  const DirHandle sub = dir.make_subdir("checkpoints");
  CHECK(sub.path() == tmp / "checkpoints");
  CHECK(sub.create_new("x"));
  CHECK_FALSE(sub.create_new("x"));
  CHECK(dir.create_subdir("new"));
  CHECK_FALSE(dir.create_subdir("new"));
}
