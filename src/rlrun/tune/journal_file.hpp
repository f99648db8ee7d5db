#pragma once
// Optuna's JournalFileStorage (optuna/storages/_journal/file.py, Optuna 3.1): a study is a log
// file, one JSON object per line, each an operation (journal_replay.hpp); replaying the lines
// in order gives the study. Writers append whole lines under Optuna's default lock,
// JournalFileSymlinkLock: the symbolic link `<file>.lock` -> `<file>` exists while a process
// holds it (symlink() is atomic, also on NFS), released by renaming it away and unlinking. So
// rlrun and Optuna processes can write one study file side by side.
//
// Beyond Optuna 3.1: a lock left behind by a process killed while holding it (kill -9 in the
// few microseconds of an append) is broken after `kLockGracePeriod` seconds, as Optuna 4's
// grace_period does; appends take milliseconds, so an older lock has no living holder.
//
// The file may come from anyone (docs/security.md): lines are read with a bounded length and
// parsed as data; a damaged line is an error naming the file and line, never a crash.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rlrun::tune {

inline constexpr double kLockGracePeriod = 30.0;           // seconds
inline constexpr size_t kMaxJournalLineBytes = 1 << 20;    // one operation
inline constexpr uint64_t kMaxJournalBytes = 1ull << 32;   // the whole study (4 GiB)

class JournalFile {
 public:
  // Creates the file when it does not exist (as Optuna does).
  explicit JournalFile(std::string path);
  const std::string& path() const { return path_; }

  // The operations after the first `lines_read` lines; advances it. A last line without its
  // newline is another process's append in progress: left for the next read.
  std::vector<nlohmann::json> read(uint64_t& lines_read);

  // Holds the lock for its lifetime (RAII). Reading is allowed with or without it.
  class Lock {
   public:
    explicit Lock(const JournalFile& file);
    ~Lock();
    Lock(const Lock&) = delete;
    Lock& operator=(const Lock&) = delete;

   private:
    std::string lock_path_;
  };

  // Appends the operations as lines in one write + fsync. The caller holds a Lock.
  void append_locked(const std::vector<nlohmann::json>& operations);
  // Takes the lock for one append.
  void append(const std::vector<nlohmann::json>& operations);

 private:
  std::string path_;
  uint64_t offset_ = 0;      // byte offset of line `offset_line_`
  uint64_t offset_line_ = 0;
};

// Python's json.dumps text for one operation: NaN/Infinity written as Python writes them.
std::string python_json_text(const nlohmann::json& value);
// Reads one line as Python's json.loads would (NaN, Infinity, -Infinity accepted, as floats).
nlohmann::json parse_python_json(const std::string& line, const std::string& where);

}  // namespace rlrun::tune
