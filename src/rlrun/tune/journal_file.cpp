#include "rlrun/tune/journal_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <random>
#include <thread>
#include <tuple>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/regular_file.hpp"

namespace rlrun::tune {
namespace {

std::string errno_text() { return std::strerror(errno); }

// A fresh name beside the lock for its release (Optuna: <file>.lock<uuid4>.rename).
std::string unique_suffix() {
  static thread_local std::mt19937_64 rng(std::random_device{}() ^ static_cast<uint64_t>(::getpid())
                                                                       << 32);
  char text[40];
  std::snprintf(text, sizeof text, "%016llx%016llx", static_cast<unsigned long long>(rng()),
                static_cast<unsigned long long>(rng()));
  return text;
}

// The lock's age in seconds (its own mtime, not its target's), or -1 when it is gone.
double lock_age(int dirfd, const std::string& lock_name) {
  struct stat st {};
  if (::fstatat(dirfd, lock_name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0) return -1;
  const auto now = std::chrono::system_clock::now().time_since_epoch();
  const double now_s = std::chrono::duration<double>(now).count();
  return now_s -
         (static_cast<double>(st.st_mtim.tv_sec) + 1e-9 * static_cast<double>(st.st_mtim.tv_nsec));
}

// Removes a lock by renaming it to a fresh name first (as Optuna's release), so that two
// processes breaking the same stale lock cannot remove a new one by accident... except in the
// window between the age check and the rename, which a 30 s grace period makes moot.
void remove_lock(int dirfd, const std::string& lock_name) {
  const std::string away = lock_name + unique_suffix() + ".rename";
  if (::renameat(dirfd, lock_name.c_str(), dirfd, away.c_str()) == 0)
    ::unlinkat(dirfd, away.c_str(), 0);
}

void write_all(int fd, const std::string& text, const std::string& path) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw RuntimeFailure("cannot append to " + path + ": " + errno_text());
    }
    done += static_cast<size_t>(n);
  }
}

void python_text(const nlohmann::json& v, std::string& out) {
  switch (v.type()) {
    case nlohmann::json::value_t::object: {
      out += '{';
      bool first = true;
      for (auto it = v.begin(); it != v.end(); ++it) {
        if (!first) out += ", ";
        first = false;
        out +=
            nlohmann::json(it.key()).dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
        out += ": ";
        python_text(it.value(), out);
      }
      out += '}';
      return;
    }
    case nlohmann::json::value_t::array: {
      out += '[';
      for (size_t i = 0; i < v.size(); ++i) {
        if (i) out += ", ";
        python_text(v[i], out);
      }
      out += ']';
      return;
    }
    case nlohmann::json::value_t::number_float: {
      const double x = v.get<double>();
      if (std::isnan(x))
        out += "NaN";
      else if (std::isinf(x))
        out += x > 0 ? "Infinity" : "-Infinity";
      else
        out += v.dump();
      return;
    }
    default:
      // ensure_ascii as Python's json.dumps default.
      out += v.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
  }
}

// Python's NaN / Infinity / -Infinity tokens (outside strings) become marker strings that
// nlohmann can parse; restore_non_finite turns them back into doubles.
constexpr const char* kNanMarker = "\x01NaN";
constexpr const char* kInfMarker = "\x01Infinity";
constexpr const char* kNegInfMarker = "\x01-Infinity";

std::string mark_non_finite(const std::string& line, const std::string& where) {
  std::string out;
  out.reserve(line.size());
  bool in_string = false;
  int depth = 0;  // brackets open outside strings (kMaxJournalDepth)
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (in_string) {
      out += c;
      if (c == '\\' && i + 1 < line.size())
        out += line[++i];
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '[' || c == '{') {
      if (++depth > kMaxJournalDepth)
        throw RuntimeFailure(where + ": JSON nested deeper than " +
                             std::to_string(kMaxJournalDepth) +
                             " levels (the journal is damaged; an operation is a few levels deep)");
    } else if (c == ']' || c == '}') {
      --depth;
    }
    if (c == '"') {
      in_string = true;
      out += c;
    } else if (line.compare(i, 3, "NaN") == 0) {
      out += "\"\\u0001NaN\"";
      i += 2;
    } else if (line.compare(i, 8, "Infinity") == 0) {
      out += "\"\\u0001Infinity\"";
      i += 7;
    } else if (line.compare(i, 9, "-Infinity") == 0) {
      out += "\"\\u0001-Infinity\"";
      i += 8;
    } else {
      out += c;
    }
  }
  return out;
}

void restore_non_finite(nlohmann::json& v) {
  if (v.is_string()) {
    const auto& s = v.get_ref<const std::string&>();
    if (s == kNanMarker)
      v = std::nan("");
    else if (s == kInfMarker)
      v = HUGE_VAL;
    else if (s == kNegInfMarker)
      v = -HUGE_VAL;
  } else if (v.is_structured()) {
    for (auto& child : v) restore_non_finite(child);
  }
}

}  // namespace

std::string python_json_text(const nlohmann::json& value) {
  std::string out;
  python_text(value, out);
  return out;
}

nlohmann::json parse_python_json(const std::string& line, const std::string& where) {
  nlohmann::json j = nlohmann::json::parse(mark_non_finite(line, where), nullptr, false);
  if (j.is_discarded()) throw RuntimeFailure(where + ": not a JSON line (the journal is damaged)");
  restore_non_finite(j);
  return j;
}

JournalFile::JournalFile(std::string path) : path_(std::move(path)) {
  std::tie(dir_, name_) = DirHandle::open_parent(path_);
  open_regular_file(dir_.fd(), name_, O_WRONLY | O_CREAT | O_APPEND, path_);
}

std::vector<nlohmann::json> JournalFile::read(uint64_t& lines_read) {
  std::vector<nlohmann::json> out;
  read(lines_read, [&](nlohmann::json&& op, const std::string&) { out.push_back(std::move(op)); });
  return out;
}

void JournalFile::read(uint64_t& lines_read,
                       const std::function<void(nlohmann::json&&, const std::string&)>& apply) {
  if (lines_read < offset_line_) {  // reading from an earlier line: start over
    offset_ = 0;
    offset_line_ = 0;
  }
  const FileDescriptor file = open_regular_file(dir_.fd(), name_, O_RDONLY, path_);
  if (!file) throw RuntimeFailure("cannot read the study journal " + path_ + ": it is gone");
  const int fd = file.get();
  struct stat st {};
  ::fstat(fd, &st);
  if (static_cast<uint64_t>(st.st_size) > kMaxJournalBytes)
    throw RuntimeFailure(path_ + " is larger than " + describe_bytes(kMaxJournalBytes) +
                         ", the most rlrun reads of a study journal (docs/security.md)");
  std::string pending;
  uint64_t position = offset_;
  uint64_t line_number = offset_line_;
  const auto too_long = [&] {
    return RuntimeFailure(path_ + ":" + std::to_string(line_number + 1) + ": a line longer than " +
                          std::to_string(kMaxJournalLineBytes) + " bytes (the journal is damaged)");
  };
  char buffer[1 << 16];
  // Only what the file held when this read began: one appended meanwhile waits for the next.
  while (position + pending.size() < static_cast<uint64_t>(st.st_size)) {
    const ssize_t n =
        ::pread(fd, buffer, sizeof buffer, static_cast<off_t>(position + pending.size()));
    if (n < 0) {
      if (errno == EINTR) continue;
      throw RuntimeFailure("cannot read " + path_ + ": " + errno_text());
    }
    if (n == 0) break;
    size_t start = 0;
    for (size_t i = 0; i < static_cast<size_t>(n); ++i) {
      if (buffer[i] != '\n') continue;
      pending.append(buffer + start, i - start);
      if (pending.size() > kMaxJournalLineBytes) throw too_long();
      const uint64_t line_bytes = pending.size() + 1;
      if (line_number >= lines_read) {
        const std::string where = path_ + ":" + std::to_string(line_number + 1);
        nlohmann::json op = parse_python_json(pending, where);
        if (!op.is_object()) throw RuntimeFailure(where + ": an operation is a JSON object");
        apply(std::move(op), where);
      }
      ++line_number;
      position += line_bytes;
      pending.clear();
      start = i + 1;
    }
    pending.append(buffer + start, static_cast<size_t>(n) - start);
    if (pending.size() > kMaxJournalLineBytes) throw too_long();
  }
  offset_ = position;
  offset_line_ = line_number;
  lines_read = std::max(lines_read, line_number);
}

JournalFile::Lock::Lock(const JournalFile& file) : file_(file), lock_name_(file.name_ + ".lock") {
  // Optuna's target is the file's path as given; any target works, the link is the lock.
  const int dirfd = file.dir_.fd();
  double sleep_s = 0.001;
  for (;;) {
    if (::symlinkat(file.path().c_str(), dirfd, lock_name_.c_str()) == 0) return;
    if (errno != EEXIST)
      throw RuntimeFailure("cannot lock the study journal (" + file.dir_.child(lock_name_) +
                           "): " + errno_text());
    if (lock_age(dirfd, lock_name_) > kLockGracePeriod) {
      remove_lock(dirfd, lock_name_);
      continue;
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(sleep_s));
    sleep_s = std::min(sleep_s * 2, 1.0);
  }
}

JournalFile::Lock::~Lock() { remove_lock(file_.dir_.fd(), lock_name_); }

void JournalFile::repair_tail(int fd) const {
  struct stat st {};
  if (::fstat(fd, &st) != 0 || st.st_size == 0) return;
  const uint64_t size = static_cast<uint64_t>(st.st_size);
  // The last line, looked for within one line's bound (a longer one the readers refuse).
  const uint64_t window = std::min<uint64_t>(size, kMaxJournalLineBytes + 1);
  std::string tail(window, '\0');
  if (::pread(fd, tail.data(), window, static_cast<off_t>(size - window)) !=
      static_cast<ssize_t>(window))
    throw RuntimeFailure("cannot read " + path_ + ": " + errno_text());
  if (tail.back() == '\n') return;
  const size_t newline = tail.rfind('\n');
  if (newline == std::string::npos && window < size)
    throw RuntimeFailure(path_ + ": its last line is longer than " +
                         std::to_string(kMaxJournalLineBytes) + " bytes (the journal is damaged)");
  const std::string fragment = newline == std::string::npos ? tail : tail.substr(newline + 1);
  bool whole = false;  // an operation that lacks only its newline: Optuna 3.1 reads it
  try {
    whole = parse_python_json(fragment, path_).is_object();
  } catch (const RuntimeFailure&) {
  }
  if (whole)
    write_all(fd, "\n", path_);
  else if (::ftruncate(fd, static_cast<off_t>(size - fragment.size())) != 0)
    throw RuntimeFailure("cannot cut the half-written last line of " + path_ + ": " + errno_text());
}

void JournalFile::append_locked(const std::vector<nlohmann::json>& operations) {
  std::string text;
  for (const auto& op : operations) {
    text += python_json_text(op);
    text += '\n';
  }
  // Read and write: repair_tail reads the last line.
  const FileDescriptor file = open_regular_file(dir_.fd(), name_, O_RDWR | O_APPEND, path_);
  if (!file) throw RuntimeFailure("cannot append to " + path_ + ": it is gone");
  repair_tail(file.get());
  write_all(file.get(), text, path_);
  ::fsync(file.get());
}

void JournalFile::append(const std::vector<nlohmann::json>& operations) {
  Lock lock(*this);
  append_locked(operations);
}

}  // namespace rlrun::tune
