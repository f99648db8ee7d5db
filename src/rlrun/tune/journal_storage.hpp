#pragma once
// A study journal opened for reading and writing: Optuna's JournalStorage
// (optuna/storages/_journal/storage.py) over a JournalFile. Every write appends one operation
// and replays what the file holds since the last read, so the state seen is always the file's.
//
// `Transaction` holds the file lock across a read-decide-write sequence (taking a waiting trial,
// creating the next trial only while the study's trial budget allows it): Optuna's appends take
// the same lock, so such a sequence is atomic against rlrun and Optuna writers alike.
#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "rlrun/tune/journal_file.hpp"
#include "rlrun/tune/journal_replay.hpp"

namespace rlrun::tune {

// Local time as Python's datetime.now().isoformat(timespec="microseconds").
std::string now_iso();
// A fresh worker id: a random UUID4 and the process id ("<uuid>-<pid>").
std::string new_worker_id();

class JournalStorage {
 public:
  explicit JournalStorage(const std::string& path, std::string worker_id = new_worker_id());

  const std::string& path() const { return file_.path(); }
  const std::string& worker_id() const { return replay_.worker_id(); }
  // Reads what other processes appended.
  void sync();
  const JournalReplay& state() const { return replay_; }

  class Transaction {
   public:
    explicit Transaction(JournalStorage& storage);
    ~Transaction();
    Transaction(const Transaction&) = delete;
    Transaction& operator=(const Transaction&) = delete;

   private:
    JournalStorage& storage_;
    JournalFile::Lock lock_;
  };

  // Optuna's create_study with load_if_exists=True: the id of the study with this name,
  // created when missing. A study with another direction is refused (RuntimeFailure).
  int64_t create_or_load_study(const std::string& name, StudyDirection direction);
  void set_study_user_attr(int64_t study_id, const std::string& key, const nlohmann::json& value);
  void set_study_system_attr(int64_t study_id, const std::string& key, const nlohmann::json& value);

  // A new RUNNING trial started now (Optuna's create_new_trial without a template).
  int64_t create_running_trial(int64_t study_id);
  // Optuna's enqueue_trial: a WAITING trial whose parameters are fixed (system attribute
  // "fixed_params": {name: external value}), plus further system attributes.
  int64_t enqueue_trial(int64_t study_id, const nlohmann::json& fixed_params,
                        const nlohmann::json& system_attrs = nlohmann::json::object());
  // Writes RUNNING for a WAITING trial; true when this worker's line came first (owns it).
  bool claim_waiting_trial(int64_t trial_id);

  void set_trial_param(int64_t trial_id, const std::string& name, double internal,
                       const Distribution& distribution);
  void set_trial_state(int64_t trial_id, TrialState state,
                       std::optional<double> value = std::nullopt);
  void report(int64_t trial_id, int64_t step, double value);
  void set_trial_user_attr(int64_t trial_id, const std::string& key, const nlohmann::json& value);
  void set_trial_system_attr(int64_t trial_id, const std::string& key, const nlohmann::json& value);

 private:
  void write(nlohmann::json op);

  JournalFile file_;
  JournalReplay replay_;
  uint64_t lines_read_ = 0;
  int lock_depth_ = 0;
};

}  // namespace rlrun::tune
