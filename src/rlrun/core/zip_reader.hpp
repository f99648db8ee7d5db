#pragma once
// Reading zip files that may come from anyone (model files, checkpoints: docs/security.md) with
// libzip, without trusting what the archive says about itself:
//  * the member list is checked when the archive opens: at most kMaxZipMembers members, names
//    of at most kMaxZipNameBytes printable bytes, relative, without a `..` component or a
//    backslash, each name once;
//  * a member's declared (uncompressed) size is only a claim: callers compare it with their own
//    limits before allocating, ZipMemberReader then reads it in caller-sized pieces and refuses
//    a member that decompresses to more or fewer bytes than declared, or fails its CRC;
//  * only stored and deflated members are decompressed (what libzip, Python's zipfile and
//    numpy.savez write): other methods (bzip2, xz, ...) have decoders whose memory depends on
//    parameters in the stream, and encrypted members are refused.
// Every error is a RuntimeFailure naming the file and the member. libzip's own memory when it
// opens an archive is proportional to the central directory, which libzip checks lies inside
// the file (zip_open.c: _zip_read_eocd / _zip_read_eocd64), so it is bounded by the file size.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

typedef struct zip zip_t;
typedef struct zip_file zip_file_t;

namespace rlrun {

inline constexpr std::size_t kMaxZipMembers = 65536;
inline constexpr std::size_t kMaxZipNameBytes = 512;

struct ZipEntry {
  uint64_t index = 0;  // libzip's index
  std::string name;
  uint64_t size = 0;       // declared uncompressed size (untrusted)
  bool directory = false;  // a name ending in '/': no data
  int32_t method = 0;      // compression method (ZIP_CM_*)
  bool encrypted = false;
};

class ZipReader {
 public:
  // Opens and checks the member list. Throws RuntimeFailure.
  explicit ZipReader(const std::string& path);
  // An archive held in memory (a zip inside a zip: torch's files inside SB3's, core/
  // torch_state_dict.hpp), with the same checks; `name` stands for its path in messages.
  ZipReader(std::vector<uint8_t> bytes, const std::string& name);
  ~ZipReader();
  ZipReader(const ZipReader&) = delete;
  ZipReader& operator=(const ZipReader&) = delete;

  const std::string& path() const { return path_; }
  const std::vector<ZipEntry>& entries() const { return entries_; }
  const ZipEntry* find(const std::string& name) const;

  // The whole member; refuses one declared larger than `max_bytes` before reading it.
  std::vector<uint8_t> read(const ZipEntry& entry, uint64_t max_bytes) const;

  // "<path>: member '<name>'" for messages, the name made printable.
  std::string describe(const ZipEntry& entry) const;

 private:
  friend class ZipMemberReader;
  void list_members();  // the checks at the top of this file

  std::string path_;
  std::vector<uint8_t> memory_;  // the archive's bytes when opened from memory
  zip_t* zip_ = nullptr;
  std::vector<ZipEntry> entries_;
};

// One member's data, read sequentially; the member must end exactly at its declared size.
class ZipMemberReader {
 public:
  ZipMemberReader(const ZipReader& archive, const ZipEntry& entry);
  ~ZipMemberReader();
  ZipMemberReader(const ZipMemberReader&) = delete;
  ZipMemberReader& operator=(const ZipMemberReader&) = delete;

  uint64_t remaining() const { return entry_.size - position_; }
  // Fills `out` with the next `n` bytes (n <= remaining()), reading in bounded pieces.
  void read(uint8_t* out, std::size_t n);
  // Checks that the data ends here: no byte beyond the declared size, and libzip's CRC check
  // (done when the stream reaches its end: zip_source_crc.c) passes.
  void expect_end();

 private:
  [[noreturn]] void fail(const std::string& why) const;
  const ZipReader& archive_;
  const ZipEntry& entry_;
  zip_file_t* file_ = nullptr;
  uint64_t position_ = 0;
};

}  // namespace rlrun
