#pragma once
// A zip archive of stored (uncompressed) members, built in memory with the same bytes for the
// same members (fixed timestamps): the container of torch.save()'s files
// (core/torch_file_writer.hpp). torch's own writer (caffe2/serialize/inline_container.cc,
// PyTorchStreamWriter) stores every record uncompressed and pads the local header's extra field
// so that each record's data starts at a multiple of 64 bytes, which lets torch map a record
// into memory; `alignment` does the same. Members over 4 GiB or more than 65535 members (zip64)
// are refused. The format: PKWARE's APPNOTE.TXT, sections 4.3.7 (local file header),
// 4.3.12 (central directory header) and 4.3.16 (end of central directory record).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace rlrun {

using StoredZipMember = std::pair<std::string, std::vector<uint8_t>>;

// Members in the given order. Throws RuntimeFailure for an archive zip32 cannot hold.
std::vector<uint8_t> stored_zip(const std::vector<StoredZipMember>& members,
                                std::size_t alignment = 1);

// The CRC-32 of zip (ISO 3309, polynomial 0xEDB88320 reflected), as zlib's crc32().
uint32_t zip_crc32(const uint8_t* data, std::size_t size);

}  // namespace rlrun
