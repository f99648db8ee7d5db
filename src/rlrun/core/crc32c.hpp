#pragma once
// CRC-32C (Castagnoli, polynomial 0x1EDC6F41, reflected 0x82F63B78), the checksum of TFRecord
// files (TensorBoard's event files), and the "masked" form TFRecord stores: a CRC of data that
// itself holds CRCs is easy to get wrong by accident, so TensorFlow rotates and offsets it
// (tensorflow/core/lib/hash/crc32c.h, Mask()).
#include <cstdint>
#include <string_view>

namespace rlrun {

uint32_t crc32c(std::string_view data);
// ((crc >> 15) | (crc << 17)) + 0xa282ead8, as TFRecord writes it.
uint32_t masked_crc32c(std::string_view data);

}  // namespace rlrun
