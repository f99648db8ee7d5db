#include "rlrun/core/zip_archive.hpp"

#include <zip.h>

#include <cstdio>
#include <filesystem>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/zip_reader.hpp"

namespace rlrun {

void write_zip_atomic(const std::string& path, const ZipMembers& members) {
  const std::string temp = path + ".tmp";
  std::error_code ec;
  std::filesystem::remove(temp, ec);
  int error = 0;
  zip_t* zip = zip_open(temp.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  if (!zip) {
    zip_error_t ze;
    zip_error_init_with_code(&ze, error);
    const std::string why = zip_error_strerror(&ze);
    zip_error_fini(&ze);
    throw RuntimeFailure("cannot create " + temp + ": " + why);
  }
  for (const auto& [name, data] : members) {
    // libzip reads the buffer at zip_close time; `members` outlives that call.
    zip_source_t* source = zip_source_buffer(zip, data.data(), data.size(), 0);
    if (!source || zip_file_add(zip, name.c_str(), source, ZIP_FL_OVERWRITE | ZIP_FL_ENC_UTF_8) < 0) {
      if (source) zip_source_free(source);
      const std::string why = zip_strerror(zip);
      zip_discard(zip);
      throw RuntimeFailure("cannot add " + name + " to " + temp + ": " + why);
    }
  }
  if (zip_close(zip) < 0) {
    const std::string why = zip_strerror(zip);
    zip_discard(zip);
    std::filesystem::remove(temp, ec);
    throw RuntimeFailure("cannot write " + path + ": " + why);
  }
  std::filesystem::rename(temp, path, ec);
  if (ec) throw RuntimeFailure("cannot rename " + temp + " to " + path + ": " + ec.message());
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
