#pragma once
// A minimal Protocol Buffers encoder (the wire format of
// https://protobuf.dev/programming-guides/encoding/): varints, 64-bit doubles, 32-bit floats and
// length-delimited bytes / nested messages. Enough to write TensorBoard's Event and Summary
// messages without a protobuf library or generated code; each caller names the field numbers
// of the .proto it follows.
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace rlrun {

class ProtoWriter {
 public:
  // Wire types: 0 varint, 1 64-bit, 2 length-delimited, 5 32-bit.
  ProtoWriter& varint(int field, uint64_t value) {
    key(field, 0);
    raw_varint(value);
    return *this;
  }
  // int32/int64/enum fields: negative values are sign-extended to 64 bits, as protobuf does.
  ProtoWriter& int64(int field, int64_t value) {
    return varint(field, static_cast<uint64_t>(value));
  }
  ProtoWriter& boolean(int field, bool value) { return varint(field, value ? 1 : 0); }
  ProtoWriter& float64(int field, double value) {
    key(field, 1);
    uint64_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    for (int i = 0; i < 8; ++i) bytes_.push_back(static_cast<char>(bits >> (8 * i)));
    return *this;
  }
  ProtoWriter& float32(int field, float value) {
    key(field, 5);
    uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    for (int i = 0; i < 4; ++i) bytes_.push_back(static_cast<char>(bits >> (8 * i)));
    return *this;
  }
  ProtoWriter& bytes(int field, std::string_view data) {
    key(field, 2);
    raw_varint(data.size());
    bytes_.append(data);
    return *this;
  }
  ProtoWriter& message(int field, const ProtoWriter& nested) { return bytes(field, nested.bytes_); }

  const std::string& str() const { return bytes_; }

 private:
  void key(int field, int wire_type) {
    raw_varint((static_cast<uint64_t>(field) << 3) | static_cast<uint64_t>(wire_type));
  }
  void raw_varint(uint64_t value) {
    while (value >= 0x80) {
      bytes_.push_back(static_cast<char>((value & 0x7F) | 0x80));
      value >>= 7;
    }
    bytes_.push_back(static_cast<char>(value));
  }
  std::string bytes_;
};

}  // namespace rlrun
