#include "rlrun/core/zip_archive.hpp"

#include <zip.h>

#include <cstdio>
#include <filesystem>

#include "rlrun/core/errors.hpp"

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

ZipMembers read_zip(const std::string& path) {
  if (!std::filesystem::exists(path)) throw RuntimeFailure(path + ": no such file");
  int error = 0;
  zip_t* zip = zip_open(path.c_str(), ZIP_RDONLY, &error);
  if (!zip) {
    zip_error_t ze;
    zip_error_init_with_code(&ze, error);
    const std::string why = zip_error_strerror(&ze);
    zip_error_fini(&ze);
    throw RuntimeFailure(path + ": not a readable model file (" + why + ")");
  }
  ZipMembers members;
  const zip_int64_t count = zip_get_num_entries(zip, 0);
  for (zip_int64_t i = 0; i < count; ++i) {
    zip_stat_t st;
    if (zip_stat_index(zip, i, 0, &st) != 0) continue;
    std::vector<uint8_t> data(st.size);
    zip_file_t* file = zip_fopen_index(zip, i, 0);
    if (!file || (st.size > 0 && zip_fread(file, data.data(), st.size) != static_cast<zip_int64_t>(st.size))) {
      if (file) zip_fclose(file);
      zip_close(zip);
      throw RuntimeFailure(path + ": cannot read member " + st.name);
    }
    zip_fclose(file);
    members[st.name] = std::move(data);
  }
  zip_close(zip);
  return members;
}

}  // namespace rlrun
