#pragma once
// Cairo RGB24 pixels -> planar YUV 4:2:0 (yuv420p), the layout H.264 encoders take. Done here
// rather than by ffmpeg's swscale because it is the hot path of recording: for 600x400 frames
// swscale's generic converter cost more per frame than drawing and pipe together, and the
// planar frame is 2.7x smaller to pipe than RGB. BT.601 limited range ("TV" levels, Y 16-235,
// chroma 16-240), with the 8-bit integer coefficients of ITU-R BT.601 as commonly tabulated
// (e.g. Keith Jack, "Video Demystified", ch. 3); chroma is the mean of each 2x2 block.
#include <cstdint>

namespace rlrun {

// `width` and `height` must be even. `out` holds width*height*3/2 bytes: the Y plane, then U,
// then V, each row-major without padding. `stride_pixels` is the distance between input rows.
void rgb24_to_yuv420p(const uint32_t* pixels, int stride_pixels, int width, int height,
                      uint8_t* out);

}  // namespace rlrun
