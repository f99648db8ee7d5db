// CRC-32C and the TFRecord framing of TensorBoard event files, against published check values.
#include <catch2/catch.hpp>

#include "rlrun/core/crc32c.hpp"
#include "rlrun/core/protobuf_writer.hpp"
#include "rlrun/runtime/io/tensorboard/event_file.hpp"

using namespace rlrun;

TEST_CASE("crc32c: the Castagnoli check values", "[core][tensorboard]") {
  CHECK(crc32c("") == 0u);
  CHECK(crc32c("123456789") == 0xE3069283u);  // the standard check value of CRC-32C
  // RFC 3720 (iSCSI) B.4: 32 bytes of zeros, and of 0xFF.
  CHECK(crc32c(std::string(32, '\0')) == 0x8A9136AAu);
  CHECK(crc32c(std::string(32, '\xff')) == 0x62A8AB43u);
  // TFRecord's mask: rotate right by 15, add 0xa282ead8.
  const uint32_t crc = crc32c("123456789");
  CHECK(masked_crc32c("123456789") == ((crc >> 15) | (crc << 17)) + 0xa282ead8u);
}

TEST_CASE("tfrecord: length, its CRC, the data, its CRC, little-endian", "[core][tensorboard]") {
  const std::string record = tfrecord("abc");
  REQUIRE(record.size() == 8 + 4 + 3 + 4);
  CHECK(record.substr(0, 8) == std::string("\x03\0\0\0\0\0\0\0", 8));
  const uint32_t length_crc = masked_crc32c(record.substr(0, 8));
  CHECK(static_cast<unsigned char>(record[8]) == (length_crc & 0xFF));
  CHECK(static_cast<unsigned char>(record[11]) == (length_crc >> 24));
  CHECK(record.substr(12, 3) == "abc");
  const uint32_t data_crc = masked_crc32c("abc");
  CHECK(static_cast<unsigned char>(record[15]) == (data_crc & 0xFF));
  CHECK(static_cast<unsigned char>(record[18]) == (data_crc >> 24));
}

TEST_CASE("protobuf writer: the wire format's examples", "[core][tensorboard]") {
  // protobuf.dev encoding guide: field 1 = 150 is 08 96 01; field 2 = "testing" is 12 07 ...
  CHECK(ProtoWriter().varint(1, 150).str() == std::string("\x08\x96\x01"));
  CHECK(ProtoWriter().bytes(2, "testing").str() == std::string("\x12\x07testing"));
  // A negative int64 takes ten bytes (two's complement, sign-extended).
  CHECK(ProtoWriter().int64(1, -1).str().size() == 11);
  CHECK(ProtoWriter().float32(2, 1.0f).str() == std::string("\x15\x00\x00\x80\x3f", 5));
  CHECK(ProtoWriter().float64(1, 1.0).str() ==
        std::string("\x09\x00\x00\x00\x00\x00\x00\xf0\x3f", 9));
}
