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

#include "rlrun/core/errors.hpp"

namespace rlrun::tune {
namespace {

// An open file descriptor, closed on every way out of its scope (a damaged line throws from
// the middle of read(): fuzz/fuzz_journal.cpp found the descriptors it used to leave open).
class OpenFile {
 public:
  explicit OpenFile(int fd) : fd_(fd) {}
  ~OpenFile() {
    if (fd_ >= 0) ::close(fd_);
  }
  OpenFile(const OpenFile&) = delete;
  OpenFile& operator=(const OpenFile&) = delete;
  int fd() const { return fd_; }

 private:
  int fd_;
};

std::string errno_text() { return std::strerror(errno); }

// A fresh name beside the lock for its release (Optuna: <file>.lock<uuid4>.rename).
std::string unique_suffix() {
  static thread_local std::mt19937_64 rng(std::random_device{}() ^
                                          static_cast<uint64_t>(::getpid()) << 32);
  char text[40];
  std::snprintf(text, sizeof text, "%016llx%016llx", static_cast<unsigned long long>(rng()),
                static_cast<unsigned long long>(rng()));
  return text;
}

// The lock's age in seconds (its own mtime, not its target's), or -1 when it is gone.
double lock_age(const std::string& lock_path) {
  struct stat st {};
  if (::lstat(lock_path.c_str(), &st) != 0) return -1;
  const auto now = std::chrono::system_clock::now().time_since_epoch();
  const double now_s = std::chrono::duration<double>(now).count();
  return now_s - (static_cast<double>(st.st_mtim.tv_sec) + 1e-9 * static_cast<double>(st.st_mtim.tv_nsec));
}

// Removes a lock by renaming it to a fresh name first (as Optuna's release), so that two
// processes breaking the same stale lock cannot remove a new one by accident... except in the
// window between the age check and the rename, which a 30 s grace period makes moot.
void remove_lock(const std::string& lock_path) {
  const std::string away = lock_path + unique_suffix() + ".rename";
  if (::rename(lock_path.c_str(), away.c_str()) == 0) ::unlink(away.c_str());
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
        out += nlohmann::json(it.key()).dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
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
      if (std::isnan(x)) out += "NaN";
      else if (std::isinf(x)) out += x > 0 ? "Infinity" : "-Infinity";
      else out += v.dump();
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

std::string mark_non_finite(const std::string& line) {
  std::string out;
  out.reserve(line.size());
  bool in_string = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (in_string) {
      out += c;
      if (c == '\\' && i + 1 < line.size()) out += line[++i];
      else if (c == '"') in_string = false;
      continue;
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
    if (s == kNanMarker) v = std::nan("");
    else if (s == kInfMarker) v = HUGE_VAL;
    else if (s == kNegInfMarker) v = -HUGE_VAL;
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
  nlohmann::json j = nlohmann::json::parse(mark_non_finite(line), nullptr, false);
  if (j.is_discarded()) throw RuntimeFailure(where + ": not a JSON line (the journal is damaged)");
  restore_non_finite(j);
  return j;
}

JournalFile::JournalFile(std::string path) : path_(std::move(path)) {
  const int fd = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) throw RuntimeFailure("cannot open the study journal " + path_ + ": " + errno_text());
  ::close(fd);
}

std::vector<nlohmann::json> JournalFile::read(uint64_t& lines_read) {
  if (lines_read < offset_line_) {  // reading from an earlier line: start over
    offset_ = 0;
    offset_line_ = 0;
  }
  const OpenFile file(::open(path_.c_str(), O_RDONLY | O_CLOEXEC));
  const int fd = file.fd();
  if (fd < 0) throw RuntimeFailure("cannot read the study journal " + path_ + ": " + errno_text());
  struct stat st {};
  ::fstat(fd, &st);
  if (static_cast<uint64_t>(st.st_size) > kMaxJournalBytes) {
    throw RuntimeFailure(path_ + " is larger than " + std::to_string(kMaxJournalBytes >> 30) +
                         " GiB: not a study journal rlrun reads");
  }
  std::vector<nlohmann::json> out;
  std::string pending;
  uint64_t position = offset_;
  uint64_t line_number = offset_line_;
  char buffer[1 << 16];
  bool done = false;
  while (!done) {
    const ssize_t n = ::pread(fd, buffer, sizeof buffer, static_cast<off_t>(position + pending.size()));
    if (n < 0) {
      if (errno == EINTR) continue;
      throw RuntimeFailure("cannot read " + path_ + ": " + errno_text());
    }
    if (n == 0) break;
    size_t start = 0;
    for (size_t i = 0; i < static_cast<size_t>(n); ++i) {
      if (buffer[i] != '\n') continue;
      pending.append(buffer + start, i - start);
      const uint64_t line_bytes = pending.size() + 1;
      if (line_number >= lines_read) {
        const std::string where = path_ + ":" + std::to_string(line_number + 1);
        nlohmann::json op = parse_python_json(pending, where);
        if (!op.is_object()) throw RuntimeFailure(where + ": an operation is a JSON object");
        out.push_back(std::move(op));
      }
      ++line_number;
      position += line_bytes;
      pending.clear();
      start = i + 1;
    }
    pending.append(buffer + start, static_cast<size_t>(n) - start);
    if (pending.size() > kMaxJournalLineBytes) {
      throw RuntimeFailure(path_ + ":" + std::to_string(line_number + 1) + ": a line longer than " +
                           std::to_string(kMaxJournalLineBytes) + " bytes (the journal is damaged)");
    }
  }
  offset_ = position;
  offset_line_ = line_number;
  lines_read = std::max(lines_read, line_number);
  return out;
}

JournalFile::Lock::Lock(const JournalFile& file) : lock_path_(file.path() + ".lock") {
  // Optuna's target is the file's path as given; any target works, the link is the lock.
  double sleep_s = 0.001;
  for (;;) {
    if (::symlink(file.path().c_str(), lock_path_.c_str()) == 0) return;
    if (errno != EEXIST)
      throw RuntimeFailure("cannot lock the study journal (" + lock_path_ + "): " + errno_text());
    if (lock_age(lock_path_) > kLockGracePeriod) {
      remove_lock(lock_path_);
      continue;
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(sleep_s));
    sleep_s = std::min(sleep_s * 2, 1.0);
  }
}

JournalFile::Lock::~Lock() { remove_lock(lock_path_); }

void JournalFile::append_locked(const std::vector<nlohmann::json>& operations) {
  std::string text;
  for (const auto& op : operations) {
    text += python_json_text(op);
    text += '\n';
  }
  const OpenFile file(::open(path_.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC));
  if (file.fd() < 0) throw RuntimeFailure("cannot append to " + path_ + ": " + errno_text());
  write_all(file.fd(), text, path_);
  ::fsync(file.fd());
}

void JournalFile::append(const std::vector<nlohmann::json>& operations) {
  Lock lock(*this);
  append_locked(operations);
}

}  // namespace rlrun::tune
