#include "rlrun/runtime/io/tensorboard/png_size.hpp"

namespace rlrun {

std::pair<int, int> png_size(const std::string& png) {
  // 8-byte signature, then the IHDR chunk: length (4), "IHDR", width (4, big-endian), height.
  if (png.size() < 24 || png.compare(1, 3, "PNG") != 0 || png.compare(12, 4, "IHDR") != 0)
    return {0, 0};
  const auto be32 = [&](size_t at) {
    return (static_cast<int>(static_cast<unsigned char>(png[at])) << 24) |
           (static_cast<unsigned char>(png[at + 1]) << 16) |
           (static_cast<unsigned char>(png[at + 2]) << 8) | static_cast<unsigned char>(png[at + 3]);
  };
  return {be32(16), be32(20)};
}

}  // namespace rlrun
