#pragma once
// Opening and reading the files that run directories and studies hold (docs/security.md, "Run
// directories and studies"). Such a directory may come from anyone, so a name in it is never
// followed as a symbolic link (O_NOFOLLOW: a planted `log.txt -> ~/.bashrc` is refused, not
// appended to) and must name a regular file: a FIFO would block its reader forever and
// /dev/zero never ends. The open itself cannot block (O_NONBLOCK until fstat(2) has shown a
// regular file), and what is read is bounded (read_bounded, core/line_reader.hpp).
#include <cstdint>
#include <string>

#include "rlrun/core/file_descriptor.hpp"

namespace rlrun {

// Opens `name` relative to the directory `dirfd` (AT_FDCWD: the working directory) with
// `flags` (O_RDONLY, or O_WRONLY with O_CREAT, O_APPEND, O_EXCL, O_TRUNC as needed; O_TRUNC is
// applied only once the file is known to be regular). Returns an empty descriptor when `name`
// does not exist and `flags` has no O_CREAT. Throws RuntimeFailure naming `shown` when `name`
// is a symbolic link or not a regular file, or cannot be opened (errno's name and text).
FileDescriptor open_regular_file(int dirfd, const std::string& name, int flags,
                                 const std::string& shown);

// All of an open file, at most `max_bytes`: a longer one is a RuntimeFailure naming `shown`
// and the bound (reading stops one byte past it, so a huge file costs nothing).
std::string read_bounded(int fd, uint64_t max_bytes, const std::string& shown);

// The refusal of a file over its bound: "<shown> is larger than <bound>, the most rlrun reads
// of it (docs/security.md)".
[[noreturn]] void refuse_oversized(const std::string& shown, uint64_t max_bytes);

// "256 MiB", "64 KiB", "17 bytes".
std::string describe_bytes(uint64_t bytes);

}  // namespace rlrun
