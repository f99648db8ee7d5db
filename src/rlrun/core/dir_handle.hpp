#pragma once
// A directory of a run or study, held open: every name in it is looked up relative to the
// descriptor (openat(2), mkdirat, unlinkat, renameat, fdopendir), never followed as a symbolic
// link, and every file must be regular (core/regular_file.hpp). Run directories and studies
// may come from anyone (docs/security.md, "Run directories and studies"): a planted
// `checkpoints -> ~/elsewhere` is refused, not written into (nor cleaned up: keep-N deletes
// only inside the real checkpoints/), and a FIFO or a link to /dev/zero is refused, not read.
//
// Where trust ends: a path the user names is resolved as usual up to its last component (their
// own directories and links: `--out ~/scratch/runs` may pass through a link); the run
// directory or study itself, and everything inside it, is opened without following links.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rlrun/core/checked_file.hpp"
#include "rlrun/core/file_descriptor.hpp"
#include "rlrun/core/line_reader.hpp"

namespace rlrun {

// What a name in a directory is, the name itself (a link is a link, not what it points to).
enum class EntryKind { kMissing, kRegular, kDirectory, kSymlink, kOther };

class DirHandle {
 public:
  // kRefuse: the last component must be a directory itself (a run directory, a study);
  // kFollow: it may be a link to one (a directory the user names to search, an out_dir).
  enum class LastLink { kRefuse, kFollow };
  struct Entry {
    std::string name;
    EntryKind kind;
  };

  DirHandle() = default;
  // Throws RuntimeFailure naming the path when it is missing, not a directory, or (kRefuse) a
  // symbolic link.
  static DirHandle open(const std::string& path, LastLink last = LastLink::kRefuse);
  // The directory holding `path` (resolved as usual: the user's own path) and `path`'s last
  // component, which must be a file name.
  static std::pair<DirHandle, std::string> open_parent(const std::string& path);

  bool is_open() const { return static_cast<bool>(fd_); }
  int fd() const { return fd_.get(); }
  // The path it was opened by, for messages; child(name) is that path and name joined.
  const std::string& path() const { return path_; }
  std::string child(const std::string& name) const;

  // `name` must be one plain component (no '/', not "." or ".."): RuntimeFailure otherwise.
  EntryKind kind(const std::string& name) const;
  // Every entry but "." and "..", sorted by name (at most 2^20: RuntimeFailure beyond).
  std::vector<Entry> list() const;
  // The subdirectory `name`; nullopt when it does not exist. RuntimeFailure when it is a link
  // or not a directory.
  std::optional<DirHandle> subdir(const std::string& name) const;
  // The same, created first (mode 0777 less the umask) when it does not exist.
  DirHandle make_subdir(const std::string& name) const;
  // A new subdirectory `name` (mkdirat: atomic); nullopt when `name` exists already.
  std::optional<DirHandle> create_subdir(const std::string& name) const;

  // The regular file `name` for reading; an empty descriptor when it does not exist.
  FileDescriptor open_for_reading(const std::string& name) const;
  // All of `name`, at most `max_bytes` (RuntimeFailure beyond); nullopt when it does not exist.
  std::optional<std::string> read(const std::string& name, uint64_t max_bytes) const;
  // `name` line by line within the bounds of core/line_reader.hpp; nullopt when it does not
  // exist.
  std::optional<LineReader> read_lines(
      const std::string& name, uint64_t max_bytes, size_t max_line_bytes,
      LineReader::LongLines long_lines = LineReader::LongLines::kRefuse) const;

  // The regular file `name` for writing, created when missing.
  CheckedFile open_for_writing(const std::string& name, CheckedFile::Mode mode) const;
  // A new file `name` for appending (O_EXCL); nullopt when `name` exists already.
  std::optional<CheckedFile> create_new(const std::string& name) const;
  // Replaces `name` atomically: a fresh O_EXCL temporary `.<name>.XXXXXX.tmp` here, every write
  // checked, fsync, renameat. A link at `name` is replaced, never followed; a FIFO, device or
  // directory there is refused. On failure `name` keeps its contents and no temporary stays.
  void write_atomic(const std::string& name, std::string_view text) const;
  // unlinkat: a link is removed itself. False when `name` was missing or could not be removed.
  bool remove(const std::string& name) const noexcept;
  // "/proc/self/fd/<fd>/<name>": a path to `name` in this very directory (the kernel resolves
  // /proc/self/fd/N to the open directory, whatever its path names by now), for libraries that
  // take only a path (libzip). In this process only.
  std::string proc_path(const std::string& name) const;

 private:
  DirHandle(FileDescriptor fd, std::string path) : fd_(std::move(fd)), path_(std::move(path)) {}

  FileDescriptor fd_;
  std::string path_;
};

}  // namespace rlrun
