#pragma once
// SB3's rules for image observations (stable_baselines3/common/preprocessing.py): which Box a
// CNN reads as an image, and which axis holds its channels.
//  * is_image_space: a Box of three dimensions; unless the images are already normalized
//    (normalize_images false), a Box of dtype uint8 bounded by 0 and 255.
//  * is_image_space_channels_first: the smallest dimension is the channel axis; first means
//    channels-first (C, H, W), anything else channels-last (H, W, C) — which SB3 transposes
//    with VecTransposeImage and rlrun's CNN reads in place (nn/nature_cnn.hpp).
#include <optional>
#include <string>

#include "rlrun/nn/nature_cnn.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

// Whether a space is a uint8 Box bounded by 0 and 255 exactly: pixels as Gymnasium's image
// wrappers and SB3's is_image_space want them (any number of dimensions).
bool is_pixel_box(const Space& space);

// The image a CNN sees in observations of `space`, or nullopt when SB3 would not call the space
// an image.
std::optional<ImageInput> image_input(const Space& space, bool normalize_images);

// The same, or std::invalid_argument with SB3's NatureCNN message (what to use instead, and
// normalize_images: false for images that are normalized already).
ImageInput require_image_input(const Space& space, bool normalize_images);

}  // namespace rlrun
