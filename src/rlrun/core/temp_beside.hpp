#pragma once
// A temporary file beside the file it will replace, for writes that must be all or nothing
// (write file, check, rename over the target: POSIX rename is atomic within a directory). The
// name is fresh (mkostemps: .<name>.XXXXXX<suffix>, created with O_EXCL), so a file or symlink
// someone planted in the directory is never followed or reused, and two writers of the same
// target never share a temporary. Its mode is that of any new file (0666 less the umask), not
// mkstemp's 0600, so the renamed file looks like one written directly.
#include <string>

namespace rlrun {

class DirHandle;  // core/dir_handle.hpp

struct TempBeside {
  int fd = -1;       // open for writing, close-on-exec
  std::string path;  // <dir of target>/.<name of target>.XXXXXX<suffix>
};

// Throws RuntimeFailure naming the target and the reason (e.g. the directory is missing).
TempBeside create_temp_beside(const std::string& target, const std::string& suffix = ".tmp");

// The same inside an open directory (openat with O_EXCL|O_NOFOLLOW, mode 0666 less the umask):
// `.<name>.XXXXXX<suffix>` beside `name` in `dir`; `path` is then the temporary's name there.
TempBeside create_temp_in(const DirHandle& dir, const std::string& name,
                          const std::string& suffix = ".tmp");

}  // namespace rlrun
