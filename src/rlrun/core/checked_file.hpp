#pragma once
// A file written with every write checked, for the files a run appends to as it goes
// (progress.csv, the monitor files, evaluations.csv). std::ofstream and stdio remember a failed
// write only in a flag nobody reads, so a full disk went unnoticed until the next model file;
// here text is collected in memory and flush() hands it to write(2) at once, turning a short or
// failed write into a RuntimeFailure that names the file and the error ("cannot write
// runs/x/progress.csv: No space left on device (ENOSPC)"). The training then stops (exit 1),
// its last checkpoint untouched.
//
// Most of these files live in run directories, which may come from anyone (docs/security.md):
// run_file() opens them without following a symbolic link at their name, and only a regular
// file (core/regular_file.hpp), so a planted `log.txt -> ~/.bashrc` or a FIFO is refused, not
// appended to or waited on. The constructor opens a path the user named (`eval --csv`, which
// may be /dev/stdout or a pipe) as it is.
#include <string>
#include <string_view>

#include "rlrun/core/file_descriptor.hpp"

namespace rlrun {

// strerror text and the errno's name: "No space left on device (ENOSPC)".
std::string describe_errno(int error);

// For a file written at the end of a command (eval --csv): fails now, with the RuntimeFailure
// CheckedFile would give then ("cannot write /proc/x/y.csv: No such file or directory"), when
// `path` cannot be opened for writing. Its directory is made as the writer would; an existing
// file keeps its content (opened without O_TRUNC), a new one is removed again; a FIFO or device
// (/dev/stdout) is left to the write.
void check_writable_file(const std::string& path);

class CheckedFile {
 public:
  enum class Mode { kTruncate, kAppend };

  CheckedFile() = default;
  // Opens the user's `path` (creating it, mode 0666 less the umask). Throws RuntimeFailure with
  // the reason.
  CheckedFile(std::string path, Mode mode);
  // Opens a file of a run directory the same way, refusing a symbolic link at `path` and a file
  // that is not regular.
  static CheckedFile run_file(std::string path, Mode mode);
  // Takes over `fd`, a regular file open for writing (core/dir_handle.hpp opens them);
  // `path` names it in messages.
  static CheckedFile adopt(FileDescriptor fd, std::string path);
  // Writes what is still buffered (errors ignored: a destructor cannot report them) and closes.
  ~CheckedFile();
  CheckedFile(CheckedFile&& other) noexcept;
  CheckedFile& operator=(CheckedFile&& other) noexcept;
  CheckedFile(const CheckedFile&) = delete;
  CheckedFile& operator=(const CheckedFile&) = delete;

  bool is_open() const { return fd_ >= 0; }
  const std::string& path() const { return path_; }

  // Buffers text; nothing reaches the file before flush().
  CheckedFile& operator<<(std::string_view text) {
    buffer_.append(text);
    return *this;
  }
  CheckedFile& operator<<(char c) {
    buffer_.push_back(c);
    return *this;
  }
  // Writes the buffer (all of it, or throws RuntimeFailure naming the file and errno).
  void flush();
  // flush(), then close(2), also checked (NFS reports some write errors only there).
  void close();

 private:
  void release() noexcept;
  std::string path_;
  int fd_ = -1;
  std::string buffer_;
};

}  // namespace rlrun
