#pragma once
// What ffprobe says of a recorded video's first stream, for the tests that record through the
// real rlrun: "codec,width,height,frames" (e.g. "h264,600,400,51"), the frames counted by
// decoding; "" with ffprobe's error when it cannot read the file.
#include <string>

#include "runtime/cli_runner.hpp"

namespace rlrun::testing {

inline std::string probe_video(const std::string& path) {
  return run_command(
             "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
             "stream=codec_name,width,height,nb_read_frames -of csv=p=0 '" +
             path + "'")
      .output;
}

}  // namespace rlrun::testing
