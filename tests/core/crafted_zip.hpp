#pragma once
// Writes the hostile zip files the reader tests need, with libzip itself: members whose
// declared size is a lie, deflate bombs, corrupt deflate streams, names rlrun never writes.
// A "raw" member is handed to libzip as already-deflated data with the sizes and CRC we choose
// (a zip source whose stat reports ZIP_CM_DEFLATE: zip_close.c add_data then copies the bytes
// as they are instead of compressing them).
#include <zip.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace rlrun::testing {

struct CraftedMember {
  std::string name;
  std::vector<uint8_t> data;  // stored as-is (store/deflate), or the raw deflate stream
  bool deflate = true;
  bool raw = false;            // `data` is a raw deflate stream; the sizes below are written
  uint64_t declared_size = 0;  // raw only: the uncompressed size the zip claims
  uint32_t crc = 0;            // raw only
};

inline std::vector<uint8_t> bytes_of(const std::string& text) {
  return std::vector<uint8_t>(text.begin(), text.end());
}

// A raw deflate stream (RFC 1951, no zlib header: zip's method 8) of `data`.
inline std::vector<uint8_t> raw_deflate(const std::vector<uint8_t>& data) {
  z_stream z{};
  if (deflateInit2(&z, 9, Z_DEFLATED, -15, 9, Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::runtime_error("deflateInit2");
  std::vector<uint8_t> out(deflateBound(&z, data.size()) + 16);
  z.next_in = const_cast<Bytef*>(data.data());
  z.avail_in = static_cast<uInt>(data.size());
  z.next_out = out.data();
  z.avail_out = static_cast<uInt>(out.size());
  deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

// A raw deflate stream that inflates to `prefix` followed by `zeros` zero bytes, a few KB per
// GB of zeros: one full-flushed (self-contained, byte-aligned) block of 1 MiB of zeros repeated.
// Sets `crc` to the CRC-32 of the whole inflated data.
inline std::vector<uint8_t> deflate_bomb(const std::vector<uint8_t>& prefix, uint64_t zeros,
                                         uint32_t& crc) {
  constexpr uint64_t kChunk = 1 << 20;
  const std::vector<uint8_t> chunk_zeros(kChunk, 0);
  z_stream z{};
  deflateInit2(&z, 9, Z_DEFLATED, -15, 9, Z_DEFAULT_STRATEGY);
  std::vector<uint8_t> buffer(kChunk + 1024);
  const auto flush_block = [&](const uint8_t* in, size_t n, int mode) {
    z.next_in = const_cast<Bytef*>(in);
    z.avail_in = static_cast<uInt>(n);
    z.next_out = buffer.data();
    z.avail_out = static_cast<uInt>(buffer.size());
    deflate(&z, mode);
    return std::vector<uint8_t>(buffer.begin(), buffer.begin() + (buffer.size() - z.avail_out));
  };
  std::vector<uint8_t> out = flush_block(prefix.data(), prefix.size(), Z_FULL_FLUSH);
  const std::vector<uint8_t> block = flush_block(chunk_zeros.data(), kChunk, Z_FULL_FLUSH);
  const uint32_t crc_chunk = static_cast<uint32_t>(crc32(0, chunk_zeros.data(), kChunk));
  crc = static_cast<uint32_t>(crc32(0, prefix.data(), static_cast<uInt>(prefix.size())));
  for (uint64_t done = 0; done + kChunk <= zeros; done += kChunk) {
    out.insert(out.end(), block.begin(), block.end());
    crc = static_cast<uint32_t>(crc32_combine(crc, crc_chunk, kChunk));
  }
  const std::vector<uint8_t> end = flush_block(nullptr, 0, Z_FINISH);
  out.insert(out.end(), end.begin(), end.end());
  deflateEnd(&z);
  return out;
}

namespace detail {

struct RawSource {
  std::vector<uint8_t> data;
  uint64_t declared_size;
  uint32_t crc;
  size_t position = 0;
};

inline zip_int64_t raw_source_callback(void* state, void* data, zip_uint64_t len,
                                       zip_source_cmd_t cmd) {
  auto* s = static_cast<RawSource*>(state);
  switch (cmd) {
    case ZIP_SOURCE_OPEN: s->position = 0; return 0;
    case ZIP_SOURCE_READ: {
      const size_t n = std::min<size_t>(len, s->data.size() - s->position);
      std::memcpy(data, s->data.data() + s->position, n);
      s->position += n;
      return static_cast<zip_int64_t>(n);
    }
    case ZIP_SOURCE_CLOSE: return 0;
    case ZIP_SOURCE_STAT: {
      auto* st = static_cast<zip_stat_t*>(data);
      zip_stat_init(st);
      st->valid = ZIP_STAT_SIZE | ZIP_STAT_COMP_SIZE | ZIP_STAT_COMP_METHOD | ZIP_STAT_CRC |
                  ZIP_STAT_ENCRYPTION_METHOD | ZIP_STAT_MTIME;
      st->size = s->declared_size;
      st->comp_size = s->data.size();
      st->comp_method = ZIP_CM_DEFLATE;
      st->encryption_method = ZIP_EM_NONE;
      st->crc = s->crc;
      st->mtime = 0;
      return sizeof(zip_stat_t);
    }
    case ZIP_SOURCE_ERROR: return 2 * sizeof(int);
    case ZIP_SOURCE_FREE: delete s; return 0;
    case ZIP_SOURCE_SUPPORTS:
      return zip_source_make_command_bitmap(ZIP_SOURCE_OPEN, ZIP_SOURCE_READ, ZIP_SOURCE_CLOSE,
                                            ZIP_SOURCE_STAT, ZIP_SOURCE_ERROR, ZIP_SOURCE_FREE, -1);
    default: return -1;
  }
}

}  // namespace detail

// Writes `members` in order to `path` (replacing it).
inline void write_crafted_zip(const std::string& path, const std::vector<CraftedMember>& members) {
  int error = 0;
  zip_t* zip = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  if (!zip) throw std::runtime_error("cannot create " + path);
  for (const CraftedMember& m : members) {
    zip_source_t* source = nullptr;
    if (m.raw) {
      zip_error_t ze;
      zip_error_init(&ze);
      source = zip_source_function_create(
          detail::raw_source_callback, new detail::RawSource{m.data, m.declared_size, m.crc}, &ze);
      zip_error_fini(&ze);
    } else {
      source = zip_source_buffer(zip, m.data.data(), m.data.size(), 0);
    }
    const zip_int64_t index =
        source ? zip_file_add(zip, m.name.c_str(), source, ZIP_FL_ENC_GUESS) : -1;
    if (index < 0) {
      const std::string why = zip_strerror(zip);
      if (source) zip_source_free(source);
      zip_discard(zip);
      throw std::runtime_error("cannot add " + m.name + ": " + why);
    }
    if (!m.raw)
      zip_set_file_compression(zip, static_cast<zip_uint64_t>(index),
                               m.deflate ? ZIP_CM_DEFLATE : ZIP_CM_STORE, 0);
  }
  if (zip_close(zip) < 0) {
    const std::string why = zip_strerror(zip);
    zip_discard(zip);
    throw std::runtime_error("cannot write " + path + ": " + why);
  }
}

}  // namespace rlrun::testing
