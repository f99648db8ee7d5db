#pragma once
// The study state a journal's operations give when replayed in order: Optuna's
// JournalStorageReplayResult (optuna/storages/_journal/storage.py, Optuna 3.1), with its rules:
//   * a study name created twice keeps the first (the second writer gets "already exists");
//   * trial ids count over the whole journal, trial numbers within each study;
//   * an operation on a finished trial is ignored (and is an error for the worker that wrote it);
//   * the first RUNNING state written for a WAITING trial wins: the worker whose line came first
//     owns it (how several workers take enqueued trials without a lock of their own);
//   * a parameter whose distribution does not fit an earlier trial's is ignored.
// Operations come from a file anyone may have written: every field is checked; a bad one is a
// RuntimeFailure naming the operation, never a crash.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rlrun/tune/frozen_trial.hpp"

namespace rlrun::tune {

// Optuna's JournalOperation.
enum class JournalOperation : int {
  kCreateStudy = 0,
  kDeleteStudy = 1,
  kSetStudyUserAttr = 2,
  kSetStudySystemAttr = 3,
  kCreateTrial = 4,
  kSetTrialParam = 5,
  kSetTrialStateValues = 6,
  kSetTrialIntermediateValue = 7,
  kSetTrialUserAttr = 8,
  kSetTrialSystemAttr = 9,
};

struct StudyRecord {
  int64_t study_id = 0;
  std::string name;
  std::vector<StudyDirection> directions;
  nlohmann::json user_attrs = nlohmann::json::object();
  nlohmann::json system_attrs = nlohmann::json::object();
  std::vector<int64_t> trial_ids;  // in number order
  // Parameter name -> the trial of lowest number that has it: Optuna checks a new parameter's
  // distribution against that one (a lookup, not a scan of every trial per operation).
  std::map<std::string, int64_t> first_trial_with_param;
};

// The most trials a replay holds (each is a few hundred bytes to a few KiB).
inline constexpr size_t kMaxJournalTrials = 1000000;
// The memory a replay may keep, estimated as operations are applied (a trial 1 KiB plus its
// operation, a parameter 256 bytes, an intermediate value 64, an attribute by its JSON:
// json_charge in journal_replay.cpp): a journal from anyone cannot make `tune report` or a
// worker hold much more than this (and the copy of the trials a report or sampler takes). A
// real study of 5 500 trials with 3 parameters and 20 reports each is charged about 25 MiB.
inline constexpr uint64_t kMaxJournalStateBytes = uint64_t{256} << 20;

class JournalReplay {
 public:
  explicit JournalReplay(std::string worker_id) : worker_id_(std::move(worker_id)) {}

  // Applies operations read from `origin` (for messages). Throws RuntimeFailure for a damaged
  // operation, and for a rejected operation this worker wrote (its own mistake).
  void apply(const std::vector<nlohmann::json>& operations, const std::string& origin);
  // One operation, as read (a journal is replayed line by line: journal_file.hpp).
  void apply(const nlohmann::json& operation, const std::string& origin) {
    apply_one(operation, origin);
  }

  const std::string& worker_id() const { return worker_id_; }
  std::optional<int64_t> find_study(const std::string& name) const;
  std::vector<std::string> study_names() const;  // in creation order
  const StudyRecord& study(int64_t study_id) const;
  const FrozenTrial& trial(int64_t trial_id) const;
  // The study's trials in number order (copies: samplers get a stable snapshot).
  std::vector<FrozenTrial> trials(int64_t study_id) const;
  // The trial this worker created or took last and still holds RUNNING (Optuna's owned trial).
  std::optional<int64_t> owned_trial() const { return owned_trial_; }
  std::optional<int64_t> last_created_trial() const { return last_created_trial_; }

 private:
  void apply_one(const nlohmann::json& op, const std::string& where);
  // One per kind of operation (apply_one dispatches on op_code).
  void create_study(const nlohmann::json& op, const std::string& where);
  void set_study_attr(const nlohmann::json& op, bool user, const std::string& where);
  void create_trial(const nlohmann::json& op, const std::string& where);
  void set_trial_param(const nlohmann::json& op, const std::string& where);
  void set_trial_state_values(const nlohmann::json& op, const std::string& where);
  void set_trial_intermediate_value(const nlohmann::json& op, const std::string& where);
  void set_trial_attr(const nlohmann::json& op, bool user, const std::string& where);
  bool mine(const nlohmann::json& op) const;
  bool study_exists(int64_t study_id, const nlohmann::json& op, const std::string& where) const;
  bool trial_updatable(int64_t trial_id, const nlohmann::json& op, const std::string& where) const;
  void charge(uint64_t bytes, const std::string& where);

  std::string worker_id_;
  std::map<int64_t, StudyRecord> studies_;
  int64_t next_study_id_ = 0;
  std::vector<FrozenTrial> trials_;   // index = trial id
  std::vector<int64_t> trial_study_;  // trial id -> study id
  std::optional<int64_t> owned_trial_;
  std::optional<int64_t> last_created_trial_;
  uint64_t state_bytes_ = 0;  // kMaxJournalStateBytes
};

}  // namespace rlrun::tune
