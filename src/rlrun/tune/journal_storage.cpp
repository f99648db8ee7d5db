#include "rlrun/tune/journal_storage.hpp"

#include <sys/time.h>
#include <unistd.h>

#include <cstdio>
#include <ctime>
#include <random>

#include "rlrun/core/errors.hpp"

namespace rlrun::tune {

std::string now_iso() {
  timeval tv{};
  ::gettimeofday(&tv, nullptr);
  std::tm local{};
  const time_t seconds = tv.tv_sec;
  ::localtime_r(&seconds, &local);
  char text[64];
  std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d.%06ld", local.tm_year + 1900,
                local.tm_mon + 1, local.tm_mday, local.tm_hour, local.tm_min, local.tm_sec,
                static_cast<long>(tv.tv_usec));
  return text;
}

std::string new_worker_id() {
  std::random_device device;
  std::mt19937_64 rng((static_cast<uint64_t>(device()) << 32) ^ device() ^
                      static_cast<uint64_t>(::getpid()));
  uint64_t hi = rng(), lo = rng();
  hi = (hi & ~0xF000ull) | 0x4000ull;                         // version 4
  lo = (lo & 0x3FFFFFFFFFFFFFFFull) | 0x8000000000000000ull;  // variant 10
  char text[64];
  std::snprintf(
      text, sizeof text, "%08llx-%04llx-%04llx-%04llx-%012llx-%d",
      static_cast<unsigned long long>(hi >> 32),
      static_cast<unsigned long long>((hi >> 16) & 0xFFFF),
      static_cast<unsigned long long>(hi & 0xFFFF), static_cast<unsigned long long>(lo >> 48),
      static_cast<unsigned long long>(lo & 0xFFFFFFFFFFFFull), static_cast<int>(::getpid()));
  return text;
}

namespace {

// A SET_*_ATTR operation: {"op_code": code, id_key: id, attr_key: {key: value}}.
nlohmann::json attribute_operation(JournalOperation code, const char* id_key, int64_t id,
                                   const char* attr_key, const std::string& key,
                                   const nlohmann::json& value) {
  return {{"op_code", static_cast<int>(code)}, {id_key, id}, {attr_key, {{key, value}}}};
}

}  // namespace

JournalStorage::JournalStorage(const std::string& path, std::string worker_id)
    : file_(path), replay_(std::move(worker_id)) {
  sync();
}

void JournalStorage::sync() {
  // One operation at a time: the replay's state is what stays, not the file's parsed lines.
  file_.read(lines_read_,
             [this](nlohmann::json&& op, const std::string& where) { replay_.apply(op, where); });
}

JournalStorage::Transaction::Transaction(JournalStorage& storage)
    : storage_(storage), lock_(storage.file_) {
  ++storage_.lock_depth_;
  storage_.sync();
}

JournalStorage::Transaction::~Transaction() { --storage_.lock_depth_; }

void JournalStorage::write(nlohmann::json op) {
  op["worker_id"] = replay_.worker_id();
  if (lock_depth_ > 0)
    file_.append_locked({op});
  else
    file_.append({op});
  sync();
}

int64_t JournalStorage::create_or_load_study(const std::string& name, StudyDirection direction) {
  {
    // Look and create under the journal's lock: workers started together on a fresh journal (the
    // array tasks of `rlrun tune --slurm`) would otherwise all see no study, all write a create,
    // and every one but the first be refused as a duplicate name. Optuna's own writers append
    // under the same lock, and Optuna's create_study(load_if_exists=True) loads after such a
    // refusal (optuna/study/study.py), so it agrees with whichever create came first.
    Transaction transaction(*this);
    if (!replay_.find_study(name))
      write({{"op_code", static_cast<int>(JournalOperation::kCreateStudy)},
             {"study_name", name},
             {"directions", {static_cast<int>(direction)}}});
  }
  const auto id = replay_.find_study(name);
  if (!id) throw RuntimeFailure("could not create study '" + name + "' in " + path());
  const auto& directions = replay_.study(*id).directions;
  if (directions.size() != 1 || directions[0] != direction)
    throw RuntimeFailure("study '" + name + "' in " + path() + " has another direction (or " +
                         "several objectives) than this study file says");
  return *id;
}

void JournalStorage::set_study_user_attr(int64_t study_id, const std::string& key,
                                         const nlohmann::json& value) {
  write(attribute_operation(JournalOperation::kSetStudyUserAttr, "study_id", study_id, "user_attr",
                            key, value));
}

void JournalStorage::set_study_system_attr(int64_t study_id, const std::string& key,
                                           const nlohmann::json& value) {
  write(attribute_operation(JournalOperation::kSetStudySystemAttr, "study_id", study_id,
                            "system_attr", key, value));
}

int64_t JournalStorage::create_running_trial(int64_t study_id) {
  write({{"op_code", static_cast<int>(JournalOperation::kCreateTrial)},
         {"study_id", study_id},
         {"datetime_start", now_iso()}});
  const auto id = replay_.last_created_trial();
  if (!id) throw RuntimeFailure("could not create a trial in " + path());
  return *id;
}

int64_t JournalStorage::enqueue_trial(int64_t study_id, const nlohmann::json& fixed_params,
                                      const nlohmann::json& system_attrs) {
  nlohmann::json attrs = system_attrs.is_object() ? system_attrs : nlohmann::json::object();
  attrs["fixed_params"] = fixed_params;
  write({{"op_code", static_cast<int>(JournalOperation::kCreateTrial)},
         {"study_id", study_id},
         {"datetime_start", nullptr},
         {"state", static_cast<int>(TrialState::kWaiting)},
         {"value", nullptr},
         {"values", nullptr},
         {"distributions", nlohmann::json::object()},
         {"params", nlohmann::json::object()},
         {"user_attrs", nlohmann::json::object()},
         {"system_attrs", attrs},
         {"intermediate_values", nlohmann::json::object()}});
  const auto id = replay_.last_created_trial();
  if (!id) throw RuntimeFailure("could not enqueue a trial in " + path());
  return *id;
}

bool JournalStorage::claim_waiting_trial(int64_t trial_id) {
  write({{"op_code", static_cast<int>(JournalOperation::kSetTrialStateValues)},
         {"trial_id", trial_id},
         {"state", static_cast<int>(TrialState::kRunning)},
         {"values", nullptr},
         {"datetime_start", now_iso()}});
  return replay_.owned_trial() == trial_id;
}

void JournalStorage::set_trial_param(int64_t trial_id, const std::string& name, double internal,
                                     const Distribution& distribution) {
  write({{"op_code", static_cast<int>(JournalOperation::kSetTrialParam)},
         {"trial_id", trial_id},
         {"param_name", name},
         {"param_value_internal", internal},
         {"distribution", distribution_to_json(distribution)}});
}

void JournalStorage::set_trial_state(int64_t trial_id, TrialState state,
                                     std::optional<double> value) {
  nlohmann::json op = {
      {"op_code", static_cast<int>(JournalOperation::kSetTrialStateValues)},
      {"trial_id", trial_id},
      {"state", static_cast<int>(state)},
      {"values", value ? nlohmann::json::array({*value}) : nlohmann::json(nullptr)}};
  if (state == TrialState::kRunning)
    op["datetime_start"] = now_iso();
  else if (is_finished(state))
    op["datetime_complete"] = now_iso();
  write(std::move(op));
}

void JournalStorage::report(int64_t trial_id, int64_t step, double value) {
  write({{"op_code", static_cast<int>(JournalOperation::kSetTrialIntermediateValue)},
         {"trial_id", trial_id},
         {"step", step},
         {"intermediate_value", value}});
}

void JournalStorage::set_trial_user_attr(int64_t trial_id, const std::string& key,
                                         const nlohmann::json& value) {
  write(attribute_operation(JournalOperation::kSetTrialUserAttr, "trial_id", trial_id, "user_attr",
                            key, value));
}

void JournalStorage::set_trial_system_attr(int64_t trial_id, const std::string& key,
                                           const nlohmann::json& value) {
  write(attribute_operation(JournalOperation::kSetTrialSystemAttr, "trial_id", trial_id,
                            "system_attr", key, value));
}

}  // namespace rlrun::tune
