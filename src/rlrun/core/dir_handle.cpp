#include "rlrun/core/dir_handle.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/regular_file.hpp"
#include "rlrun/core/temp_beside.hpp"

namespace rlrun {

namespace {

constexpr size_t kMaxListedEntries = size_t{1} << 20;

void check_plain_name(const std::string& name, const std::string& dir) {
  if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos ||
      name.find('\0') != std::string::npos)
    throw RuntimeFailure("'" + name + "' is not a plain file name (inside " + dir + ")");
}

[[noreturn]] void refuse_link(const std::string& shown) {
  throw RuntimeFailure(shown +
                       " is a symbolic link: rlrun does not follow links to or inside run "
                       "directories and studies (they may come from anyone; "
                       "docs/security.md); name the directory it points to if you trust it");
}

EntryKind kind_of(mode_t mode) {
  if (S_ISREG(mode)) return EntryKind::kRegular;
  if (S_ISDIR(mode)) return EntryKind::kDirectory;
  if (S_ISLNK(mode)) return EntryKind::kSymlink;
  return EntryKind::kOther;
}

// Why a directory could not be opened, `stat` being what lstat/fstatat saw (or failed to).
[[noreturn]] void refuse_directory(const std::string& shown, int error, bool seen, mode_t mode) {
  if (seen && S_ISLNK(mode)) refuse_link(shown);
  if (error == ENOENT) throw RuntimeFailure(shown + ": no such directory");
  if (error == ENOTDIR || (seen && !S_ISDIR(mode)))
    throw RuntimeFailure(shown + " is not a directory");
  throw RuntimeFailure("cannot open " + shown + ": " + describe_errno(error));
}

std::string without_trailing_slashes(std::string path) {
  while (path.size() > 1 && path.back() == '/') path.pop_back();
  return path;
}

}  // namespace

DirHandle DirHandle::open(const std::string& given, LastLink last) {
  // "run/" is "run": a trailing slash would make the kernel follow a link at the end.
  const std::string path = without_trailing_slashes(given);
  const int flags =
      O_RDONLY | O_DIRECTORY | O_CLOEXEC | (last == LastLink::kRefuse ? O_NOFOLLOW : 0);
  FileDescriptor fd(::open(path.empty() ? "." : path.c_str(), flags));
  if (!fd) {
    const int error = errno;
    struct stat st {};
    const bool seen = ::lstat(path.c_str(), &st) == 0;
    refuse_directory(path, error, seen, st.st_mode);
  }
  return DirHandle(std::move(fd), path);
}

std::pair<DirHandle, std::string> DirHandle::open_parent(const std::string& path) {
  const size_t slash = path.rfind('/');
  const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  if (name.empty() || name == "." || name == "..")
    throw RuntimeFailure("'" + path + "' does not name a file");
  if (slash == std::string::npos) {
    DirHandle here = open(".", LastLink::kFollow);
    here.path_.clear();  // child(name) is then `name` itself, as the caller wrote it
    return {std::move(here), name};
  }
  const std::string parent = slash == 0 ? "/" : path.substr(0, slash);
  return {open(parent, LastLink::kFollow), name};
}

std::string DirHandle::child(const std::string& name) const {
  if (path_.empty()) return name;
  return path_.back() == '/' ? path_ + name : path_ + "/" + name;
}

EntryKind DirHandle::kind(const std::string& name) const {
  check_plain_name(name, path_);
  struct stat st {};
  if (::fstatat(fd_.get(), name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0) return kind_of(st.st_mode);
  if (errno == ENOENT) return EntryKind::kMissing;
  throw RuntimeFailure("cannot look at " + child(name) + ": " + describe_errno(errno));
}

std::vector<DirHandle::Entry> DirHandle::list() const {
  // fdopendir takes the descriptor it is given (and moves its offset): a fresh one of ".".
  const int copy = ::openat(fd_.get(), ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  DIR* dir = copy < 0 ? nullptr : ::fdopendir(copy);
  if (!dir) {
    const int error = errno;
    if (copy >= 0) ::close(copy);
    throw RuntimeFailure("cannot list " + path_ + ": " + describe_errno(error));
  }
  std::vector<Entry> entries;
  while (const dirent* e = ::readdir(dir)) {
    const std::string name = e->d_name;
    if (name == "." || name == "..") continue;
    if (entries.size() == kMaxListedEntries) {
      ::closedir(dir);
      throw RuntimeFailure(path_ + " holds more than " + std::to_string(kMaxListedEntries) +
                           " entries, more than rlrun lists in a run directory or study");
    }
    EntryKind kind = EntryKind::kOther;
    switch (e->d_type) {
      case DT_REG: kind = EntryKind::kRegular; break;
      case DT_DIR: kind = EntryKind::kDirectory; break;
      case DT_LNK: kind = EntryKind::kSymlink; break;
      case DT_UNKNOWN: {  // some file systems do not say: ask
        struct stat st {};
        kind = ::fstatat(fd_.get(), e->d_name, &st, AT_SYMLINK_NOFOLLOW) == 0 ? kind_of(st.st_mode)
                                                                              : EntryKind::kMissing;
        break;
      }
      default: break;
    }
    if (kind != EntryKind::kMissing) entries.push_back({name, kind});
  }
  ::closedir(dir);
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return a.name < b.name; });
  return entries;
}

std::optional<DirHandle> DirHandle::subdir(const std::string& name) const {
  check_plain_name(name, path_);
  FileDescriptor fd(
      ::openat(fd_.get(), name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
  if (!fd) {
    const int error = errno;
    if (error == ENOENT) return std::nullopt;
    struct stat st {};
    const bool seen = ::fstatat(fd_.get(), name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0;
    refuse_directory(child(name), error, seen, st.st_mode);
  }
  return DirHandle(std::move(fd), child(name));
}

DirHandle DirHandle::make_subdir(const std::string& name) const {
  if (std::optional<DirHandle> made = create_subdir(name)) return std::move(*made);
  std::optional<DirHandle> existing = subdir(name);
  if (!existing) throw RuntimeFailure("cannot create " + child(name) + ": it went away meanwhile");
  return std::move(*existing);
}

std::optional<DirHandle> DirHandle::create_subdir(const std::string& name) const {
  check_plain_name(name, path_);
  if (::mkdirat(fd_.get(), name.c_str(), 0777) != 0) {
    if (errno == EEXIST) return std::nullopt;
    throw RuntimeFailure("cannot create " + child(name) + ": " + describe_errno(errno));
  }
  std::optional<DirHandle> made = subdir(name);
  if (!made) throw RuntimeFailure("cannot create " + child(name) + ": it went away meanwhile");
  return made;
}

FileDescriptor DirHandle::open_for_reading(const std::string& name) const {
  check_plain_name(name, path_);
  return open_regular_file(fd_.get(), name, O_RDONLY, child(name));
}

std::optional<std::string> DirHandle::read(const std::string& name, uint64_t max_bytes) const {
  const FileDescriptor fd = open_for_reading(name);
  if (!fd) return std::nullopt;
  return read_bounded(fd.get(), max_bytes, child(name));
}

std::optional<LineReader> DirHandle::read_lines(const std::string& name, uint64_t max_bytes,
                                                size_t max_line_bytes,
                                                LineReader::LongLines long_lines) const {
  FileDescriptor fd = open_for_reading(name);
  if (!fd) return std::nullopt;
  return LineReader(std::move(fd), child(name), max_bytes, max_line_bytes, long_lines);
}

CheckedFile DirHandle::open_for_writing(const std::string& name, CheckedFile::Mode mode) const {
  check_plain_name(name, path_);
  const int flags = O_WRONLY | O_CREAT | (mode == CheckedFile::Mode::kAppend ? O_APPEND : O_TRUNC);
  return CheckedFile::adopt(open_regular_file(fd_.get(), name, flags, child(name)), child(name));
}

std::optional<CheckedFile> DirHandle::create_new(const std::string& name) const {
  check_plain_name(name, path_);
  if (kind(name) != EntryKind::kMissing) return std::nullopt;
  try {
    return CheckedFile::adopt(
        open_regular_file(fd_.get(), name, O_WRONLY | O_CREAT | O_EXCL | O_APPEND, child(name)),
        child(name));
  } catch (const RuntimeFailure&) {
    if (kind(name) != EntryKind::kMissing) return std::nullopt;  // made by another meanwhile
    throw;
  }
}

void DirHandle::write_atomic(const std::string& name, std::string_view text) const {
  check_plain_name(name, path_);
  const std::string target = child(name);
  const EntryKind existing = kind(name);
  // A link is replaced by the rename (never followed); a FIFO or device must not become a file.
  if (existing == EntryKind::kDirectory || existing == EntryKind::kOther)
    throw RuntimeFailure("cannot write " + target + ": not a regular file");
  TempBeside temp = create_temp_in(*this, name, ".tmp");
  const auto fail = [&](const std::string& what, int error) {
    if (temp.fd >= 0) ::close(temp.fd);
    ::unlinkat(fd_.get(), temp.path.c_str(), 0);
    throw RuntimeFailure(what + target + ": " + describe_errno(error));
  };
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(temp.fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("cannot write ", n < 0 ? errno : EIO);
    done += static_cast<size_t>(n);
  }
  if (::fsync(temp.fd) != 0) fail("cannot write ", errno);
  const int fd = std::exchange(temp.fd, -1);
  if (::close(fd) != 0) fail("cannot write ", errno);
  if (::renameat(fd_.get(), temp.path.c_str(), fd_.get(), name.c_str()) != 0)
    fail("cannot rename " + child(temp.path) + " to ", errno);
}

bool DirHandle::remove(const std::string& name) const noexcept {
  if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos)
    return false;
  return ::unlinkat(fd_.get(), name.c_str(), 0) == 0;
}

std::string DirHandle::proc_path(const std::string& name) const {
  check_plain_name(name, path_);
  return "/proc/self/fd/" + std::to_string(fd_.get()) + "/" + name;
}

}  // namespace rlrun
