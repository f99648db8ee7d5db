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
// The file may come from anyone (docs/security.md): it is opened in its directory without
// following a link and must be a regular file (core/dir_handle.hpp: a `study.journal` link is
// refused, not written through; a FIFO is refused, not waited on); it is read within
// kMaxJournalBytes, one operation at a time (memory grows with the study's state, not with the
// file), lines of at most kMaxJournalLineBytes nested at most kMaxJournalDepth deep, and parsed
// as data; a damaged line is an error naming the file and line, never a crash.
//
// A half-written last line (a writer killed in the middle of its append) is not an error: every
// reader leaves it, as Optuna 3.1's read_logs does (a line that does not decode is an error only
// when another line follows it). The next append, holding the lock (so no writer is appending),
// repairs it first: a whole JSON object that lacks only its newline gets it, anything else is
// cut off. So readers and writers agree on every such file, and Optuna reads it afterwards too.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rlrun/core/dir_handle.hpp"

namespace rlrun::tune {

inline constexpr double kLockGracePeriod = 30.0;                   // seconds
inline constexpr size_t kMaxJournalLineBytes = 1 << 20;            // one operation
inline constexpr uint64_t kMaxJournalBytes = uint64_t{128} << 20;  // the whole study
// Brackets open at once in one operation (Optuna's are at most 4 deep; a user attribute may
// nest further). Deeper JSON is refused before it is parsed: the recursive walks over a parsed
// operation (and nlohmann::json's own destructor and dump) would overflow the stack.
inline constexpr int kMaxJournalDepth = 128;

class JournalFile {
 public:
  // Creates the file when it does not exist (as Optuna does). The directory holding `path` is
  // the user's (resolved as usual); the file itself must not be a link.
  explicit JournalFile(std::string path);
  const std::string& path() const { return path_; }

  // Hands `apply` each operation after the first `lines_read` lines, with "<path>:<line>";
  // advances `lines_read`. A last line without its newline is another process's append in
  // progress, or a dead writer's (see above): left for the next read.
  void read(uint64_t& lines_read,
            const std::function<void(nlohmann::json&&, const std::string&)>& apply);
  // The same, collected.
  std::vector<nlohmann::json> read(uint64_t& lines_read);

  // Holds the lock for its lifetime (RAII). Reading is allowed with or without it.
  class Lock {
   public:
    explicit Lock(const JournalFile& file);
    ~Lock();
    Lock(const Lock&) = delete;
    Lock& operator=(const Lock&) = delete;

   private:
    const JournalFile& file_;
    std::string lock_name_;  // <file>.lock in the journal's directory
  };

  // Appends the operations as lines in one write + fsync, after repairing a half-written last
  // line (see above). The caller holds a Lock.
  void append_locked(const std::vector<nlohmann::json>& operations);
  // Takes the lock for one append.
  void append(const std::vector<nlohmann::json>& operations);

 private:
  void repair_tail(int fd) const;

  DirHandle dir_;     // the directory holding the journal
  std::string name_;  // the journal's name in it
  std::string path_;
  uint64_t offset_ = 0;  // byte offset of line `offset_line_`
  uint64_t offset_line_ = 0;
};

// Python's json.dumps text for one operation: NaN/Infinity written as Python writes them.
std::string python_json_text(const nlohmann::json& value);
// Reads one line as Python's json.loads would (NaN, Infinity, -Infinity accepted, as floats).
// Throws RuntimeFailure naming `where` for a line that is not JSON or nests deeper than
// kMaxJournalDepth.
nlohmann::json parse_python_json(const std::string& line, const std::string& where);

}  // namespace rlrun::tune
