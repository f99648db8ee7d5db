#include "rlrun/core/stored_zip.hpp"

#include <array>
#include <limits>

#include "rlrun/core/errors.hpp"

namespace rlrun {

namespace {

constexpr uint32_t kLocalHeaderSignature = 0x04034b50;
constexpr uint32_t kCentralHeaderSignature = 0x02014b50;
constexpr uint32_t kEndOfCentralSignature = 0x06054b50;
constexpr uint16_t kVersionNeeded = 20;                 // 2.0: what a stored member needs
constexpr uint16_t kDosDate = (0 << 9) | (1 << 5) | 1;  // 1980-01-01, zip's earliest date
constexpr uint16_t kPaddingFieldId = 0x4246;            // "FB": the id torch's writer pads with
constexpr std::size_t kLocalHeaderBytes = 30;
constexpr std::size_t kFieldHeaderBytes = 4;

std::array<uint32_t, 256> crc_table() {
  std::array<uint32_t, 256> table{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[i] = c;
  }
  return table;
}

class ByteSink {
 public:
  explicit ByteSink(std::vector<uint8_t>& out) : out_(out) {}
  void u16(std::size_t v) {
    for (int i = 0; i < 2; ++i) out_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  void u32(std::size_t v) {
    for (int i = 0; i < 4; ++i) out_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  void text(const std::string& s) { out_.insert(out_.end(), s.begin(), s.end()); }

 private:
  std::vector<uint8_t>& out_;
};

// Bytes of extra field that put the data of a member whose local header starts at `offset`
// at a multiple of `alignment`: none, or a padding field of at least its 4-byte header.
std::size_t padding_bytes(std::size_t offset, std::size_t name_bytes, std::size_t alignment) {
  if (alignment <= 1) return 0;
  const std::size_t data_start = offset + kLocalHeaderBytes + name_bytes;
  std::size_t pad = (alignment - data_start % alignment) % alignment;
  if (pad == 0) return 0;
  while (pad < kFieldHeaderBytes) pad += alignment;
  return pad;
}

}  // namespace

uint32_t zip_crc32(const uint8_t* data, std::size_t size) {
  static const std::array<uint32_t, 256> table = crc_table();
  uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < size; ++i) c = table[(c ^ data[i]) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

std::vector<uint8_t> stored_zip(const std::vector<StoredZipMember>& members,
                                std::size_t alignment) {
  constexpr std::size_t kMax32 = std::numeric_limits<uint32_t>::max();
  if (members.size() > 0xFFFF) throw RuntimeFailure("a zip of more than 65535 members");
  std::vector<uint8_t> out;
  std::vector<uint8_t> central;
  ByteSink file(out);
  ByteSink directory(central);
  for (const auto& [name, data] : members) {
    if (name.size() > 0xFFFF || data.size() >= kMax32)
      throw RuntimeFailure("zip member '" + name + "' is too large for a zip32 archive");
    const std::size_t offset = out.size();
    if (offset >= kMax32) throw RuntimeFailure("a zip archive of more than 4 GiB");
    const uint32_t crc = zip_crc32(data.data(), data.size());
    const std::size_t pad = padding_bytes(offset, name.size(), alignment);
    // Local file header, then the name, the padding field and the data.
    file.u32(kLocalHeaderSignature);
    file.u16(kVersionNeeded);
    file.u16(0);  // flags
    file.u16(0);  // method: stored
    file.u16(0);  // time 00:00:00
    file.u16(kDosDate);
    file.u32(crc);
    file.u32(data.size());  // compressed size
    file.u32(data.size());
    file.u16(name.size());
    file.u16(pad);
    file.text(name);
    if (pad > 0) {
      file.u16(kPaddingFieldId);
      file.u16(pad - kFieldHeaderBytes);
      out.insert(out.end(), pad - kFieldHeaderBytes, uint8_t{'Z'});
    }
    out.insert(out.end(), data.begin(), data.end());
    // Its central directory header.
    directory.u32(kCentralHeaderSignature);
    directory.u16(kVersionNeeded);  // version made by: 2.0, MS-DOS attributes
    directory.u16(kVersionNeeded);
    directory.u16(0);
    directory.u16(0);
    directory.u16(0);
    directory.u16(kDosDate);
    directory.u32(crc);
    directory.u32(data.size());
    directory.u32(data.size());
    directory.u16(name.size());
    directory.u16(0);  // extra field
    directory.u16(0);  // comment
    directory.u16(0);  // disk number
    directory.u16(0);  // internal attributes
    directory.u32(0);  // external attributes
    directory.u32(offset);
    directory.text(name);
  }
  const std::size_t directory_offset = out.size();
  if (directory_offset + central.size() >= kMax32)
    throw RuntimeFailure("a zip archive of more than 4 GiB");
  out.insert(out.end(), central.begin(), central.end());
  file.u32(kEndOfCentralSignature);
  file.u16(0);  // this disk
  file.u16(0);  // the disk where the directory starts
  file.u16(members.size());
  file.u16(members.size());
  file.u32(central.size());
  file.u32(directory_offset);
  file.u16(0);  // comment
  return out;
}

}  // namespace rlrun
