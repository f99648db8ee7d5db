#include "rlrun/core/zip_reader.hpp"

#include <zip.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/plural.hpp"

namespace rlrun {

namespace {

// Pieces zip_fread fills at a time: the decompressor's output is never buffered whole.
constexpr std::size_t kReadPiece = 1 << 20;

// A name as it may appear in a message: control bytes (a terminal escape, a newline that
// would fake another message) as \xNN, at most 120 bytes.
std::string printable_name(const std::string& name) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (size_t i = 0; i < name.size() && i < 120; ++i) {
    const auto c = static_cast<unsigned char>(name[i]);
    if (c < 0x20 || c == 0x7f || c == '\\') {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    } else {
      out += static_cast<char>(c);
    }
  }
  if (name.size() > 120) out += "...";
  return out;
}

// Why `name` is not acceptable as a member of a model file ("" if it is). rlrun never extracts
// members to disk, but names are used as keys and shown in messages, and a name that could
// escape a directory marks a file that was not written by rlrun (docs/security.md).
std::string name_problem(const std::string& name) {
  if (name.empty()) return "an empty name";
  if (name.size() > kMaxZipNameBytes)
    return "a name longer than " + std::to_string(kMaxZipNameBytes) + " bytes";
  // libzip hands out names as C strings, so a NUL inside a stored name ends it there; the
  // check below sees the rest of the name as missing, and a truncated name that equals another
  // member's is refused as a duplicate.
  for (const char ch : name) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7f) return "a control character in its name";
    if (c == '\\') return "a backslash in its name";
  }
  if (name.front() == '/') return "an absolute path";
  size_t start = 0;
  while (start <= name.size()) {
    const size_t end = std::min(name.find('/', start), name.size());
    if (name.compare(start, end - start, "..") == 0) return "a '..' component in its name";
    start = end + 1;
  }
  return "";
}

}  // namespace

ZipReader::ZipReader(const std::string& path) : path_(path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw RuntimeFailure(path + ": no such file");
  if (!std::filesystem::is_regular_file(path, ec))
    throw RuntimeFailure(path + ": not a regular file");
  int error = 0;
  zip_ = zip_open(path.c_str(), ZIP_RDONLY, &error);
  if (!zip_) {
    zip_error_t ze;
    zip_error_init_with_code(&ze, error);
    const std::string why = zip_error_strerror(&ze);
    zip_error_fini(&ze);
    throw RuntimeFailure(path + ": not a readable model file (" + why + ")");
  }
  try {
    list_members();
  } catch (...) {
    zip_discard(zip_);
    throw;
  }
}

ZipReader::ZipReader(std::vector<uint8_t> bytes, const std::string& name)
    : path_(name), memory_(std::move(bytes)) {
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* source = zip_source_buffer_create(memory_.data(), memory_.size(), 0, &error);
  if (source) {
    zip_ = zip_open_from_source(source, ZIP_RDONLY, &error);
    if (!zip_) zip_source_free(source);  // zip_open_from_source keeps it only on success
  }
  if (!zip_) {
    const std::string why = zip_error_strerror(&error);
    zip_error_fini(&error);
    throw RuntimeFailure(name + ": not a readable zip archive (" + why + ")");
  }
  zip_error_fini(&error);
  try {
    list_members();
  } catch (...) {
    zip_discard(zip_);
    throw;
  }
}

void ZipReader::list_members() {
  const std::string& path = path_;
  const zip_int64_t count = zip_get_num_entries(zip_, 0);
  if (count < 0 || static_cast<uint64_t>(count) > kMaxZipMembers)
    throw RuntimeFailure(path + ": holds " + std::to_string(count) + " members, more than the " +
                         std::to_string(kMaxZipMembers) + " a model file may have");
  std::set<std::string> seen;
  entries_.reserve(static_cast<size_t>(count));
  for (zip_int64_t i = 0; i < count; ++i) {
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat_index(zip_, static_cast<zip_uint64_t>(i), 0, &st) != 0)
      throw RuntimeFailure(path + ": cannot read member " + std::to_string(i) + " (" +
                           zip_strerror(zip_) + ")");
    const uint64_t needed = ZIP_STAT_NAME | ZIP_STAT_SIZE | ZIP_STAT_COMP_METHOD;
    if ((st.valid & needed) != needed || !st.name)
      throw RuntimeFailure(path + ": member " + std::to_string(i) + " has no name or size");
    ZipEntry entry;
    entry.index = static_cast<uint64_t>(i);
    entry.name = st.name;  // a copy: libzip's string lives only as long as the archive
    entry.size = st.size;
    entry.method = st.comp_method;
    entry.encrypted =
        (st.valid & ZIP_STAT_ENCRYPTION_METHOD) && st.encryption_method != ZIP_EM_NONE;
    const std::string problem = name_problem(entry.name);
    if (!problem.empty())
      throw RuntimeFailure(path + ": member '" + printable_name(entry.name) + "' has " + problem +
                           "; not a model file written by rlrun");
    if (!seen.insert(entry.name).second)
      throw RuntimeFailure(path + ": member '" + printable_name(entry.name) +
                           "' appears twice; not a model file written by rlrun");
    entry.directory = entry.name.back() == '/';
    entries_.push_back(std::move(entry));
  }
}

ZipReader::~ZipReader() {
  if (zip_) zip_discard(zip_);  // read-only: nothing to write back
}

const ZipEntry* ZipReader::find(const std::string& name) const {
  for (const ZipEntry& e : entries_)
    if (e.name == name) return &e;
  return nullptr;
}

std::string ZipReader::describe(const ZipEntry& entry) const {
  return path_ + ": member '" + printable_name(entry.name) + "'";
}

std::vector<uint8_t> ZipReader::read(const ZipEntry& entry, uint64_t max_bytes) const {
  if (entry.size > max_bytes)
    throw RuntimeFailure(describe(entry) + " declares " + std::to_string(entry.size) +
                         " bytes, more than the " + std::to_string(max_bytes) + " allowed");
  ZipMemberReader member(*this, entry);
  std::vector<uint8_t> data(static_cast<size_t>(entry.size));
  member.read(data.data(), data.size());
  member.expect_end();
  return data;
}

ZipMemberReader::ZipMemberReader(const ZipReader& archive, const ZipEntry& entry)
    : archive_(archive), entry_(entry) {
  if (entry.encrypted) fail("is encrypted");
  if (entry.method != ZIP_CM_STORE && entry.method != ZIP_CM_DEFLATE)
    fail("uses compression method " + std::to_string(entry.method) +
         " (rlrun reads stored and deflated members)");
  file_ = zip_fopen_index(archive.zip_, entry.index, 0);
  if (!file_) fail(std::string("cannot be opened (") + zip_strerror(archive.zip_) + ")");
}

ZipMemberReader::~ZipMemberReader() {
  if (file_) zip_fclose(file_);
}

void ZipMemberReader::fail(const std::string& why) const {
  throw RuntimeFailure(archive_.describe(entry_) + " " + why);
}

void ZipMemberReader::read(uint8_t* out, std::size_t n) {
  if (n > remaining()) fail("is read beyond its declared size");  // a caller's bug
  size_t done = 0;
  while (done < n) {
    const zip_int64_t got = zip_fread(file_, out + done, std::min(n - done, kReadPiece));
    if (got < 0) fail(std::string("is corrupt (") + zip_file_strerror(file_) + ")");
    if (got == 0)
      fail("ends after " + std::to_string(position_ + done) + " of its declared " +
           count_of(static_cast<int64_t>(entry_.size), "byte"));
    done += static_cast<size_t>(got);
  }
  position_ += done;
}

void ZipMemberReader::expect_end() {
  if (remaining() != 0) fail("was not read to its end");  // a caller's bug
  uint8_t extra = 0;
  const zip_int64_t got = zip_fread(file_, &extra, 1);
  if (got < 0) fail(std::string("is corrupt (") + zip_file_strerror(file_) + ")");
  if (got > 0)
    fail("holds more data than its declared " +
         count_of(static_cast<int64_t>(entry_.size), "byte"));
}

}  // namespace rlrun
