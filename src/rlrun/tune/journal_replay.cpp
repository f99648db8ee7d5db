#include "rlrun/tune/journal_replay.hpp"

#include <cmath>

#include "rlrun/core/errors.hpp"

namespace rlrun::tune {
namespace {

[[noreturn]] void damaged(const std::string& where, const std::string& what) {
  throw RuntimeFailure(where + ": " + what + " (the study journal is damaged)");
}

const nlohmann::json& field(const nlohmann::json& op, const char* key, const std::string& where) {
  auto it = op.find(key);
  if (it == op.end()) damaged(where, std::string("missing '") + key + "'");
  return *it;
}

int64_t id_field(const nlohmann::json& op, const char* key, const std::string& where) {
  const auto& v = field(op, key, where);
  if (!v.is_number_integer() || v.get<int64_t>() < 0)
    damaged(where, std::string("'") + key + "' is not an id");
  return v.get<int64_t>();
}

std::string string_field(const nlohmann::json& op, const char* key, const std::string& where) {
  const auto& v = field(op, key, where);
  if (!v.is_string()) damaged(where, std::string("'") + key + "' is not a string");
  return v.get<std::string>();
}

double number_value(const nlohmann::json& v, const std::string& where, const char* what) {
  if (!v.is_number()) damaged(where, std::string(what) + " is not a number");
  return v.get<double>();
}

// null or a datetime text; empty for null.
std::string datetime_field(const nlohmann::json& op, const char* key, const std::string& where) {
  auto it = op.find(key);
  if (it == op.end() || it->is_null()) return "";
  if (!it->is_string() || it->get_ref<const std::string&>().size() > 64)
    damaged(where, std::string("'") + key + "' is not a date");
  return it->get<std::string>();
}

TrialState state_value(const nlohmann::json& v, const std::string& where) {
  if (!v.is_number_integer() || v.get<int64_t>() < 0 || v.get<int64_t>() > 4)
    damaged(where, "'state' is not a trial state (0-4)");
  return static_cast<TrialState>(v.get<int>());
}

std::optional<std::vector<double>> values_value(const nlohmann::json& v, const std::string& where) {
  if (v.is_null()) return std::nullopt;
  if (!v.is_array() || v.size() > 64) damaged(where, "'values' is not a list of numbers");
  std::vector<double> out;
  for (const auto& x : v) out.push_back(number_value(x, where, "a value"));
  return out;
}

// A one-key attribute map ({"key": value}), as every SET_*_ATTR operation holds.
const nlohmann::json& one_attribute(const nlohmann::json& op, const char* key,
                                    const std::string& where) {
  const auto& v = field(op, key, where);
  if (!v.is_object() || v.size() != 1)
    damaged(where, std::string("'") + key + "' is not one attribute");
  return v;
}

// What keeping a parsed JSON value costs, about (measured: an object's member ~200 bytes with
// its value, an array's element 16): 64 bytes per value, 128 more per object member (a map
// node and its key), plus the strings. The reader bounds the depth (journal_file.hpp).
uint64_t json_charge(const nlohmann::json& v) {
  uint64_t bytes = 64;
  if (v.is_string()) {
    bytes += v.get_ref<const std::string&>().size();
  } else if (v.is_object()) {
    for (auto it = v.begin(); it != v.end(); ++it)
      bytes += 128 + it.key().size() + json_charge(it.value());
  } else if (v.is_array()) {
    for (const auto& x : v) bytes += json_charge(x);
  }
  return bytes;
}

// A CREATE_TRIAL operation's trial fields (a trial may be created finished, with everything).
void read_trial_fields(const nlohmann::json& op, FrozenTrial& t, const std::string& where) {
  t.state = op.contains("state") ? state_value(op["state"], where) : TrialState::kRunning;
  if (op.contains("distributions")) {
    if (!op["distributions"].is_object()) damaged(where, "'distributions' is not a map");
    for (auto it = op["distributions"].begin(); it != op["distributions"].end(); ++it) {
      if (!it.value().is_string()) damaged(where, "a distribution is not JSON text");
      try {
        t.distributions[it.key()] = distribution_from_json(it.value().get<std::string>(), where);
      } catch (const ConfigError& e) {
        damaged(where, e.what());
      }
    }
  }
  if (op.contains("params")) {
    if (!op["params"].is_object()) damaged(where, "'params' is not a map");
    for (auto it = op["params"].begin(); it != op["params"].end(); ++it) {
      auto d = t.distributions.find(it.key());
      if (d == t.distributions.end())
        damaged(where, "parameter '" + it.key() + "' has no distribution");
      const double internal = number_value(it.value(), where, "a parameter");
      if (!contains(d->second, internal))
        damaged(where, "parameter '" + it.key() + "' is outside its distribution");
      t.params[it.key()] = internal;
    }
  }
  t.datetime_start = datetime_field(op, "datetime_start", where);
  t.datetime_complete = datetime_field(op, "datetime_complete", where);
  if (op.contains("user_attrs")) {
    if (!op["user_attrs"].is_object()) damaged(where, "'user_attrs' is not a map");
    t.user_attrs = op["user_attrs"];
  }
  if (op.contains("system_attrs")) {
    if (!op["system_attrs"].is_object()) damaged(where, "'system_attrs' is not a map");
    t.system_attrs = op["system_attrs"];
  }
  if (op.contains("intermediate_values")) {
    if (!op["intermediate_values"].is_object())
      damaged(where, "'intermediate_values' is not a map");
    for (auto it = op["intermediate_values"].begin(); it != op["intermediate_values"].end(); ++it) {
      char* end = nullptr;
      const long long step = std::strtoll(it.key().c_str(), &end, 10);
      if (it.key().empty() || *end != '\0')
        damaged(where, "an intermediate step is not an integer");
      t.intermediate_values[step] = number_value(it.value(), where, "an intermediate value");
    }
  }
  if (op.contains("values"))
    t.values = values_value(op["values"], where);
  else if (op.contains("value") && !op["value"].is_null())
    t.values = std::vector<double>{number_value(op["value"], where, "'value'")};
}

}  // namespace

void JournalReplay::charge(uint64_t bytes, const std::string& where) {
  state_bytes_ += bytes;
  if (state_bytes_ > kMaxJournalStateBytes)
    damaged(where, "the study's trials and attributes so far need more than " +
                       std::to_string(kMaxJournalStateBytes >> 20) +
                       " MiB of memory, the most rlrun keeps of a journal (docs/security.md)");
}

void JournalReplay::apply(const std::vector<nlohmann::json>& operations,
                          const std::string& origin) {
  for (const auto& op : operations) apply_one(op, origin);
}

bool JournalReplay::mine(const nlohmann::json& op) const {
  auto it = op.find("worker_id");
  return it != op.end() && it->is_string() && it->get_ref<const std::string&>() == worker_id_;
}

bool JournalReplay::study_exists(int64_t study_id, const nlohmann::json& op,
                                 const std::string& where) const {
  if (studies_.count(study_id)) return true;
  if (mine(op))
    throw RuntimeFailure(where + ": study " + std::to_string(study_id) + " does not exist");
  return false;
}

bool JournalReplay::trial_updatable(int64_t trial_id, const nlohmann::json& op,
                                    const std::string& where) const {
  if (trial_id < 0 || static_cast<size_t>(trial_id) >= trials_.size()) {
    if (mine(op))
      throw RuntimeFailure(where + ": trial " + std::to_string(trial_id) + " does not exist");
    return false;
  }
  if (is_finished(trials_[static_cast<size_t>(trial_id)].state)) {
    if (mine(op))
      throw RuntimeFailure(where + ": trial #" +
                           std::to_string(trials_[static_cast<size_t>(trial_id)].number) +
                           " has already finished and can not be updated");
    return false;
  }
  return true;
}

void JournalReplay::apply_one(const nlohmann::json& op, const std::string& origin) {
  const std::string where = origin;
  const auto& code = field(op, "op_code", where);
  if (!code.is_number_integer()) damaged(where, "'op_code' is not an integer");
  switch (static_cast<JournalOperation>(code.get<int>())) {
    case JournalOperation::kCreateStudy: return create_study(op, where);
    case JournalOperation::kDeleteStudy: {
      const int64_t id = id_field(op, "study_id", where);
      if (study_exists(id, op, where)) studies_.erase(id);
      return;
    }
    case JournalOperation::kSetStudyUserAttr: return set_study_attr(op, /*user=*/true, where);
    case JournalOperation::kSetStudySystemAttr: return set_study_attr(op, /*user=*/false, where);
    case JournalOperation::kCreateTrial: return create_trial(op, where);
    case JournalOperation::kSetTrialParam: return set_trial_param(op, where);
    case JournalOperation::kSetTrialStateValues: return set_trial_state_values(op, where);
    case JournalOperation::kSetTrialIntermediateValue:
      return set_trial_intermediate_value(op, where);
    case JournalOperation::kSetTrialUserAttr: return set_trial_attr(op, /*user=*/true, where);
    case JournalOperation::kSetTrialSystemAttr: return set_trial_attr(op, /*user=*/false, where);
  }
  damaged(where, "unknown op_code " + code.dump());
}

void JournalReplay::create_study(const nlohmann::json& op, const std::string& where) {
  const std::string name = string_field(op, "study_name", where);
  const auto& dirs = field(op, "directions", where);
  if (!dirs.is_array() || dirs.empty() || dirs.size() > 64)
    damaged(where, "'directions' is not a list");
  std::vector<StudyDirection> directions;
  for (const auto& d : dirs) {
    if (!d.is_number_integer() || d.get<int>() < 0 || d.get<int>() > 2)
      damaged(where, "a study direction is not 0, 1 or 2");
    directions.push_back(static_cast<StudyDirection>(d.get<int>()));
  }
  if (find_study(name)) {
    if (mine(op)) throw RuntimeFailure("another study with name '" + name + "' already exists");
    return;
  }
  charge(512 + name.size(), where);
  StudyRecord study;
  study.study_id = next_study_id_++;
  study.name = name;
  study.directions = directions;
  studies_[study.study_id] = std::move(study);
}

// SET_STUDY_USER_ATTR (user) or SET_STUDY_SYSTEM_ATTR.
void JournalReplay::set_study_attr(const nlohmann::json& op, bool user, const std::string& where) {
  const int64_t id = id_field(op, "study_id", where);
  const auto& attr = one_attribute(op, user ? "user_attr" : "system_attr", where);
  if (!study_exists(id, op, where)) return;
  charge(json_charge(attr), where);
  auto& target = user ? studies_[id].user_attrs : studies_[id].system_attrs;
  target.update(attr);
}

void JournalReplay::create_trial(const nlohmann::json& op, const std::string& where) {
  const int64_t study_id = id_field(op, "study_id", where);
  if (!study_exists(study_id, op, where)) return;
  if (trials_.size() >= kMaxJournalTrials)
    damaged(where, "more than " + std::to_string(kMaxJournalTrials) + " trials");
  charge(1024 + json_charge(op), where);
  StudyRecord& study = studies_[study_id];
  FrozenTrial t;
  t.trial_id = static_cast<int64_t>(trials_.size());
  t.number = static_cast<int>(study.trial_ids.size());
  read_trial_fields(op, t, where);
  for (const auto& [name, distribution] : t.distributions)
    study.first_trial_with_param.emplace(name, t.trial_id);  // kept when an earlier has it
  trials_.push_back(std::move(t));
  trial_study_.push_back(study_id);
  study.trial_ids.push_back(trials_.back().trial_id);
  if (mine(op)) {
    last_created_trial_ = trials_.back().trial_id;
    if (trials_.back().state == TrialState::kRunning) owned_trial_ = trials_.back().trial_id;
  }
}

void JournalReplay::set_trial_param(const nlohmann::json& op, const std::string& where) {
  const int64_t id = id_field(op, "trial_id", where);
  if (!trial_updatable(id, op, where)) return;
  const std::string name = string_field(op, "param_name", where);
  const double internal =
      number_value(field(op, "param_value_internal", where), where, "'param_value_internal'");
  Distribution distribution;
  try {
    distribution = distribution_from_json(string_field(op, "distribution", where), where);
  } catch (const ConfigError& e) {
    damaged(where, e.what());
  }
  if (!contains(distribution, internal))
    damaged(where, "parameter '" + name + "' is outside its distribution");
  // Optuna: the first trial (lowest number) with this parameter decides whether it fits.
  StudyRecord& study = studies_.at(trial_study_[static_cast<size_t>(id)]);
  const auto first = study.first_trial_with_param.find(name);
  if (first != study.first_trial_with_param.end() &&
      !compatible(trials_[static_cast<size_t>(first->second)].distributions.at(name),
                  distribution)) {
    if (mine(op))
      throw RuntimeFailure(where + ": parameter '" + name + "' changed its distribution");
    return;
  }
  charge(256 + name.size(), where);
  FrozenTrial& t = trials_[static_cast<size_t>(id)];
  t.params[name] = internal;
  t.distributions[name] = distribution;
  if (first == study.first_trial_with_param.end())
    study.first_trial_with_param.emplace(name, id);
  else if (t.number < trials_[static_cast<size_t>(first->second)].number)
    first->second = id;
}

void JournalReplay::set_trial_state_values(const nlohmann::json& op, const std::string& where) {
  const int64_t id = id_field(op, "trial_id", where);
  if (!trial_updatable(id, op, where)) return;
  const TrialState state = state_value(field(op, "state", where), where);
  FrozenTrial& t = trials_[static_cast<size_t>(id)];
  if (state == TrialState::kRunning && t.state == TrialState::kRunning) return;
  if (state == TrialState::kRunning) {
    t.datetime_start = datetime_field(op, "datetime_start", where);
    if (mine(op)) owned_trial_ = id;
  }
  if (is_finished(state)) t.datetime_complete = datetime_field(op, "datetime_complete", where);
  t.state = state;
  if (op.contains("values") && !op["values"].is_null())
    t.values = values_value(op["values"], where);
}

void JournalReplay::set_trial_intermediate_value(const nlohmann::json& op,
                                                 const std::string& where) {
  const int64_t id = id_field(op, "trial_id", where);
  const auto& step = field(op, "step", where);
  if (!step.is_number_integer()) damaged(where, "'step' is not an integer");
  const double value =
      number_value(field(op, "intermediate_value", where), where, "'intermediate_value'");
  if (!trial_updatable(id, op, where)) return;
  charge(64, where);
  trials_[static_cast<size_t>(id)].intermediate_values[step.get<int64_t>()] = value;
}

// SET_TRIAL_USER_ATTR (user) or SET_TRIAL_SYSTEM_ATTR.
void JournalReplay::set_trial_attr(const nlohmann::json& op, bool user, const std::string& where) {
  const int64_t id = id_field(op, "trial_id", where);
  const auto& attr = one_attribute(op, user ? "user_attr" : "system_attr", where);
  if (!trial_updatable(id, op, where)) return;
  charge(json_charge(attr), where);
  FrozenTrial& t = trials_[static_cast<size_t>(id)];
  (user ? t.user_attrs : t.system_attrs).update(attr);
}

std::optional<int64_t> JournalReplay::find_study(const std::string& name) const {
  for (const auto& [id, study] : studies_)
    if (study.name == name) return id;
  return std::nullopt;
}

std::vector<std::string> JournalReplay::study_names() const {
  std::vector<std::string> out;
  for (const auto& [id, study] : studies_) out.push_back(study.name);
  return out;
}

const StudyRecord& JournalReplay::study(int64_t study_id) const {
  auto it = studies_.find(study_id);
  if (it == studies_.end())
    throw RuntimeFailure("study " + std::to_string(study_id) + " does not exist");
  return it->second;
}

const FrozenTrial& JournalReplay::trial(int64_t trial_id) const {
  if (trial_id < 0 || static_cast<size_t>(trial_id) >= trials_.size())
    throw RuntimeFailure("trial " + std::to_string(trial_id) + " does not exist");
  return trials_[static_cast<size_t>(trial_id)];
}

std::vector<FrozenTrial> JournalReplay::trials(int64_t study_id) const {
  std::vector<FrozenTrial> out;
  for (int64_t id : study(study_id).trial_ids) out.push_back(trials_[static_cast<size_t>(id)]);
  return out;
}

}  // namespace rlrun::tune
