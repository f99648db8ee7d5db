#include "rlrun/render/video_limits.hpp"

namespace rlrun {

namespace {
std::string size_text(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}
}  // namespace

std::string check_frame_size(int width, int height) {
  if (width >= 1 && height >= 1 && width <= kMaxFrameSide && height <= kMaxFrameSide) return "";
  return "frame size " + size_text(width, height) + ": width and height must be between 1 and " +
         std::to_string(kMaxFrameSide) + " (a " + std::to_string(kMaxFrameSide) + "x" +
         std::to_string(kMaxFrameSide) + " frame already takes 64 MB)";
}

std::string check_video_size(int width, int height) {
  if (width < 2 || height < 2 || width > kMaxFrameSide || height > kMaxFrameSide)
    return "video size " + size_text(width, height) + ": width and height must be between 2 and " +
           std::to_string(kMaxFrameSide) +
           " (H.264 level limits and memory: a frame is held as RGB and yuv420p)";
  if (width % 2 != 0 || height % 2 != 0)
    return "video size " + size_text(width, height) +
           ": width and height must be even (H.264 in yuv420p stores colour per 2x2 pixels)";
  return "";
}

}  // namespace rlrun
