// VideoWriter (src/rlrun/render/video_writer.hpp): real mp4s checked with ffprobe, and the
// failure modes: ffmpeg missing, ffmpeg failing, abandoned writes. None may leave a file.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "core/scoped_process_settings.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/render/video_writer.hpp"
#include "runtime/cli_runner.hpp"

namespace fs = std::filesystem;
using rlrun::Frame;
using rlrun::VideoWriter;
using rlrun::testing::run_command;
using rlrun::testing::TempDir;

namespace {

// Sets an environment variable for the scope of the object.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_)
      ::setenv(name_, old_->c_str(), 1);
    else
      ::unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

int files_in(const std::string& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.is_regular_file();
  return n;
}

void write_frames(VideoWriter& video, Frame& frame, int n) {
  for (int i = 0; i < n; ++i) {
    frame.begin_scene(100, 100, {255, 255, 255});
    const rlrun::Point box[] = {{double(i), 10}, {double(i), 30}, {i + 20.0, 30}, {i + 20.0, 10}};
    frame.polygon(box, {0, 0, 0});
    video.write(frame);
  }
}

}  // namespace

TEST_CASE("VideoWriter writes an H.264 mp4 with every frame", "[render][video]") {
  TempDir dir("video_writer_ok");
  const std::string path = dir / "sub/clip.mp4";  // missing directories are created
  Frame frame(320, 240);
  {
    VideoWriter video(path, 320, 240, {.fps = 25});
    write_frames(video, frame, 37);
    CHECK(video.frames_written() == 37);
    CHECK_FALSE(fs::exists(path));  // still under its temporary name
    video.close();
  }
  REQUIRE(fs::exists(path));
  CHECK(files_in(dir / "sub") == 1);  // no temporary file left
  const auto probe = run_command(
      "ffprobe -v error -select_streams v:0 -count_frames -show_entries "
      "stream=codec_name,width,height,pix_fmt,nb_read_frames,r_frame_rate -of "
      "default=noprint_wrappers=1 " +
      path);
  REQUIRE(probe.exit_code == 0);
  CHECK_THAT(probe.output, Catch::Contains("codec_name=h264"));
  CHECK_THAT(probe.output, Catch::Contains("width=320"));
  CHECK_THAT(probe.output, Catch::Contains("height=240"));
  CHECK_THAT(probe.output, Catch::Contains("pix_fmt=yuv420p"));
  CHECK_THAT(probe.output, Catch::Contains("r_frame_rate=25/1"));
  CHECK_THAT(probe.output, Catch::Contains("nb_read_frames=37"));
}

TEST_CASE("VideoWriter rejects sizes H.264 cannot take and frames of another size",
          "[render][video]") {
  TempDir dir("video_writer_size");
  CHECK_THROWS_AS(VideoWriter(dir / "a.mp4", 321, 240), std::invalid_argument);
  CHECK_THROWS_AS(VideoWriter(dir / "a.mp4", 320, 240, {.fps = 0}), std::invalid_argument);
  VideoWriter video(dir / "b.mp4", 320, 240);
  Frame other(100, 100);
  CHECK_THROWS_AS(video.write(other), std::invalid_argument);
}

TEST_CASE("VideoWriter without ffmpeg on PATH names the Debian package", "[render][video]") {
  TempDir dir("video_writer_missing");
  ScopedEnv path("PATH", dir.str());  // a directory without ffmpeg
  rlrun::test::ScopedProcessSettings none([](rlrun::ProcessSettings& s) { s.ffmpeg = ""; });
  try {
    VideoWriter video(dir / "clip.mp4", 320, 240);
    FAIL("expected an error");
  } catch (const rlrun::RuntimeFailure& e) {
    CHECK_THAT(e.what(), Catch::Contains("ffmpeg"));
    CHECK_THAT(e.what(), Catch::Contains("apt-get install ffmpeg"));
  }
  CHECK(files_in(dir.str()) == 0);
}

TEST_CASE("VideoWriter reports ffmpeg's own error and leaves no file", "[render][video]") {
  TempDir dir("video_writer_fail");
  // A stand-in ffmpeg that reads a little, complains and dies, like one without libx264.
  const std::string fake = dir / "ffmpeg";
  {
    std::ofstream script(fake);
    script << "#!/bin/sh\nhead -c 1000 > /dev/null\necho 'first line' >&2\n"
              "echo \"Unknown encoder 'libx264'\" >&2\nexit 1\n";
  }
  fs::permissions(fake, fs::perms::owner_all);
  rlrun::test::ScopedProcessSettings ffmpeg([&](rlrun::ProcessSettings& s) { s.ffmpeg = fake; });
  const std::string path = dir / "out/clip.mp4";
  Frame frame(320, 240);
  try {
    VideoWriter video(path, 320, 240);
    write_frames(video, frame, 50);  // fails once the pipe breaks ...
    video.close();                   // ... or here at the latest
    FAIL("expected an error");
  } catch (const rlrun::RuntimeFailure& e) {
    CHECK_THAT(e.what(), Catch::Contains("Unknown encoder 'libx264'"));
    CHECK_THAT(e.what(), Catch::Contains(path));
  }
  CHECK(files_in(dir / "out") == 0);

  // An ffmpeg that exits 1 after reading everything fails in close().
  {
    std::ofstream script(fake);
    script << "#!/bin/sh\ncat > /dev/null\necho 'Conversion failed!' >&2\nexit 1\n";
  }
  try {
    VideoWriter video(path, 320, 240);
    write_frames(video, frame, 3);
    video.close();
    FAIL("expected an error");
  } catch (const rlrun::RuntimeFailure& e) {
    CHECK_THAT(e.what(), Catch::Contains("Conversion failed!"));
    CHECK_THAT(e.what(), Catch::Contains("exit code 1"));
  }
  CHECK(files_in(dir / "out") == 0);
}

TEST_CASE("VideoWriter abandoned before close leaves no file", "[render][video]") {
  TempDir dir("video_writer_abandon");
  Frame frame(320, 240);
  {
    VideoWriter video(dir / "clip.mp4", 320, 240);
    write_frames(video, frame, 5);
  }
  CHECK(files_in(dir.str()) == 0);
  VideoWriter empty(dir / "empty.mp4", 320, 240);
  CHECK_THROWS_AS(empty.close(), rlrun::RuntimeFailure);  // no frames: no video
  CHECK(files_in(dir.str()) == 0);
}
