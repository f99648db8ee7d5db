#include "rlrun/core/zip_archive.hpp"

#include <fcntl.h>
#include <unistd.h>
#include <zip.h>

#include <cerrno>
#include <cstdio>

#include "rlrun/core/checked_file.hpp"
#include "rlrun/core/dir_handle.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/zip_reader.hpp"

namespace rlrun {

namespace {

// libzip takes a path: `at` names `name` in the directory (DirHandle::proc_path), `shown` is
// what messages say. libzip builds the archive in a temporary of its own beside `<at>.tmp` and
// renames it there; then `.tmp` is renamed over `name` within the directory.
void write_zip_at(const DirHandle& dir, const std::string& name, const std::string& at,
                  const std::string& shown, const ZipMembers& members) {
  const std::string temp = at + ".tmp", temp_name = name + ".tmp", temp_shown = shown + ".tmp";
  dir.remove(temp_name);  // a killed writer's, or a planted file or link: never written through
  int error = 0;
  zip_t* zip = zip_open(temp.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  if (!zip) {
    zip_error_t ze;
    zip_error_init_with_code(&ze, error);
    const std::string why = zip_error_strerror(&ze);
    zip_error_fini(&ze);
    throw RuntimeFailure("cannot create " + temp_shown + ": " + why);
  }
  for (const auto& [member, data] : members) {
    // libzip reads the buffer at zip_close time; `members` outlives that call.
    zip_source_t* source = zip_source_buffer(zip, data.data(), data.size(), 0);
    if (!source ||
        zip_file_add(zip, member.c_str(), source, ZIP_FL_OVERWRITE | ZIP_FL_ENC_UTF_8) < 0) {
      if (source) zip_source_free(source);
      const std::string why = zip_strerror(zip);
      zip_discard(zip);
      throw RuntimeFailure("cannot add " + member + " to " + temp_shown + ": " + why);
    }
  }
  if (zip_close(zip) < 0) {
    const std::string why = zip_strerror(zip);
    zip_discard(zip);
    dir.remove(temp_name);
    throw RuntimeFailure("cannot write " + shown + ": " + why);
  }
  if (::renameat(dir.fd(), temp_name.c_str(), dir.fd(), name.c_str()) != 0)
    throw RuntimeFailure("cannot rename " + temp_shown + " to " + shown + ": " +
                         describe_errno(errno));
}

}  // namespace

void write_zip_atomic(const std::string& path, const ZipMembers& members) {
  const auto [dir, name] = DirHandle::open_parent(path);
  write_zip_atomic(dir, name, members);
}

void write_zip_atomic(const DirHandle& dir, const std::string& name, const ZipMembers& members) {
  // Without /proc (a chroot, say) the directory's path is the next best thing.
  const bool proc = ::access("/proc/self/fd", X_OK) == 0;
  write_zip_at(dir, name, proc ? dir.proc_path(name) : dir.child(name), dir.child(name), members);
}

ZipMembers read_zip(const std::string& path, uint64_t max_total_bytes) {
  const ZipReader archive(path);
  uint64_t total = 0;
  for (const ZipEntry& e : archive.entries())
    if (!e.directory && __builtin_add_overflow(total, e.size, &total)) total = UINT64_MAX;
  if (total > max_total_bytes)
    throw RuntimeFailure(path + ": its members declare " + std::to_string(total) +
                         " bytes, more than the " + std::to_string(max_total_bytes) + " allowed");
  ZipMembers members;
  for (const ZipEntry& e : archive.entries())
    if (!e.directory) members[e.name] = archive.read(e, e.size);
  return members;
}

}  // namespace rlrun
