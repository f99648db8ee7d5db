#pragma once
// A private temporary directory: made with mkdtemp(3) (a fresh, unpredictable name, mode 0700,
// so no other user can list it or plant a file or symlink in it) under $TMPDIR or /tmp, and
// removed with everything in it when the object goes (docs/security.md: temporary files are
// created with O_EXCL in private directories). Files inside are created with create_file(),
// which refuses to follow a symlink or to reuse an existing file.
//
// Why not a fixed name in /tmp: a name others can predict (e.g. rlrun<pid>_<n>.log) can be
// planted beforehand as a symlink, and opening it with O_CREAT|O_TRUNC then truncates
// whatever the link points at.
//
// A process killed with SIGKILL runs no destructor, so its directories stay. The name holds
// the creator's pid (<prefix><pid>-XXXXXX) so that a later process can recognise them: with
// RemoveStale::kYes the first directory made with a prefix in a process first removes this
// user's directories of that prefix whose process has ended.
#include <string>

namespace rlrun {

class PrivateTempDir {
 public:
  enum class RemoveStale { kNo, kYes };
  // Creates <tmp>/<prefix><pid>-XXXXXX. Throws RuntimeFailure naming the directory and the
  // reason.
  explicit PrivateTempDir(const std::string& prefix, RemoveStale stale = RemoveStale::kNo);
  // Removes the directory and its contents (unless keep() was called); never throws.
  ~PrivateTempDir();
  PrivateTempDir(const PrivateTempDir&) = delete;
  PrivateTempDir& operator=(const PrivateTempDir&) = delete;

  const std::string& path() const { return path_; }
  // path()/name (a plain file name, no '/').
  std::string file(const std::string& name) const;
  // Creates path()/name for writing with O_CREAT|O_EXCL|O_NOFOLLOW|O_CLOEXEC, mode 0600, and
  // returns its descriptor. Throws RuntimeFailure with the reason.
  int create_file(const std::string& name) const;
  // Leaves the directory on disk when this object goes (e.g. logs of failed runs to read).
  void keep() { keep_ = true; }

 private:
  std::string path_;
  bool keep_ = false;
};

}  // namespace rlrun
