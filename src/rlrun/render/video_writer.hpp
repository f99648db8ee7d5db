#pragma once
// MP4 video from frames: converts each frame to yuv420p (render/yuv420.hpp) and pipes it
// into the `ffmpeg` program (Debian package `ffmpeg`), which encodes H.264 with the index
// up front (+faststart), so the file plays in browsers. Nothing is linked against libav*: one
// external program, a clear error when it is missing, and its own error output when it fails.
//
// The video is written to a hidden temporary file beside the output (made with mkstemps: a
// fresh name, O_EXCL) and renamed into place only when ffmpeg has finished successfully: a
// failure or an interruption never leaves a partial file behind. The output is always a plain
// path (`file:x.mp4` is a file of that name): ffmpeg is given "file:<absolute path>", never a
// name it could read as another protocol, and is started with an argv (no shell). ffmpeg runs in its own process group, so Ctrl-C in a terminal reaches
// rlrun (which can still finish the video) and not the encoder.
#include <sys/types.h>

#include <cstdint>
#include <string>
#include <vector>

#include "rlrun/frame.hpp"

namespace rlrun {

struct VideoOptions {
  double fps = 30.0;  // frames per second of the video
  int crf = 23;       // x264 constant rate factor (lower = better and larger)
  // x264 speed preset. ultrafast: ~0.7 ms of CPU per 600x400 frame against ~1.4 (superfast)
  // and ~2.3 (veryfast); the files are about twice as large (~30 kB per second of CartPole),
  // which for flat classic-control pictures is still small. Baseline-compatible H.264.
  std::string preset = "ultrafast";
};

class VideoWriter {
 public:
  // Starts ffmpeg. Throws std::invalid_argument for a size check_video_size refuses (odd, or
  // beyond render/video_limits.hpp's bound) or fps outside (0, kMaxVideoFps], RuntimeFailure
  // when ffmpeg cannot be found or started.
  VideoWriter(std::string path, int width, int height, const VideoOptions& options = {});
  // Without close(): stops ffmpeg and removes the temporary file.
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // Appends one frame (same size as the writer). Throws RuntimeFailure with ffmpeg's error
  // output when ffmpeg has stopped.
  void write(const Frame& frame);
  // Finishes the file and renames it into place. Throws RuntimeFailure (and leaves no file)
  // when ffmpeg fails or no frame was written.
  void close();
  // Stops ffmpeg and removes the temporary file (what the destructor does).
  void abort() noexcept;

  int64_t frames_written() const { return frames_; }
  const std::string& path() const { return path_; }

  // The ffmpeg to run: $RLRUN_FFMPEG when set, else `ffmpeg` on PATH. Throws RuntimeFailure
  // naming the Debian package when there is none.
  static std::string find_ffmpeg();

 private:
  [[noreturn]] void fail(const std::string& what);
  int wait_for_exit() noexcept;
  std::string error_tail() const;

  std::string path_;
  std::string temp_path_;
  int width_, height_;
  pid_t pid_ = -1;
  int pipe_fd_ = -1;    // write end of ffmpeg's stdin
  int stderr_fd_ = -1;  // unlinked temporary file holding ffmpeg's stderr
  int64_t frames_ = 0;
  std::vector<uint8_t> yuv_;  // one converted frame, allocated once
};

}  // namespace rlrun
