#pragma once
// The frame sizes and rates rlrun records, checked before anything is allocated or ffmpeg is
// started (`rlrun record --size`, `--fps`, the experiment file's `video:` section, VideoWriter).
//
// Why 4096 per side: a frame is held as 32-bit RGB (render/frame.hpp) plus its yuv420p copy,
// so 4096 x 4096 is 64 MB + 24 MB, while 16384 x 16384 would be 1.4 GB for one frame; and
// H.264's largest level (6.2, ITU-T H.264 Table A-1) allows 139264 macroblocks per frame
// (8192 x 4352), which libx264 enforces, with browsers' decoders commonly stopping at 4096 wide.
// Even sides: yuv420p stores one chroma sample per 2 x 2 pixels.
#include <string>

namespace rlrun {

inline constexpr int kMaxFrameSide = 4096;
// Frames per second of a recorded video (a player shows at most a few hundred).
inline constexpr double kMaxVideoFps = 1000.0;

// "" when width x height can be drawn (1 .. kMaxFrameSide each), else the problem.
std::string check_frame_size(int width, int height);

// "" when width x height can be encoded as an mp4 (H.264, yuv420p): even, 2 .. kMaxFrameSide
// each; else the problem, e.g. "video size 601x400: width and height must be even (H.264
// yuv420p stores colour per 2x2 pixels)".
std::string check_video_size(int width, int height);

}  // namespace rlrun
