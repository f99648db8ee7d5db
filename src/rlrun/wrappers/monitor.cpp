#include "rlrun/wrappers/monitor.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "rlrun/core/errors.hpp"

namespace rlrun {

namespace {
// SB3 rounds r and t to 6 decimals before writing.
double round6(double v) { return std::round(v * 1e6) / 1e6; }
}  // namespace

Monitor::Monitor(EnvPtr inner, const std::string& path, double t_start,
                 std::vector<std::string> info_keywords, bool append)
    : Wrapper(std::move(inner)), t_start_(t_start), clock_start_(std::chrono::steady_clock::now()) {
  const Info& inner_info = inner_->info();
  for (const auto& key : inner_info.keys()) inner_to_own_.push_back(info_.add_key(key));
  episode_r_ = info_.add_key("episode.r");
  episode_l_ = info_.add_key("episode.l");
  episode_t_ = info_.add_key("episode.t");
  // SB3's Monitor copies each info keyword into info["episode"]; here `episode.<key>`. A key
  // the env has not declared yet (a Python env declares keys as its dicts show them) is
  // looked up again whenever new keys appear.
  keywords_ = std::move(info_keywords);
  for (const auto& keyword : keywords_) {
    keyword_inner_index_.push_back(inner_info.find(keyword));
    keyword_own_index_.push_back(info_.add_key("episode." + keyword));
  }
  if (path.empty()) return;
  // A run directory's file: not through a link, a regular file (core/checked_file.hpp).
  file_ = CheckedFile::run_file(path,
                                append ? CheckedFile::Mode::kAppend : CheckedFile::Mode::kTruncate);
  if (append) return;
  char t_start_text[64];
  std::snprintf(t_start_text, sizeof t_start_text, "%.6f", t_start_);
  file_ << "#{\"t_start\": " << t_start_text << ", \"env_id\": \"" << inner_->id() << "\"}\nr,l,t";
  for (const auto& column : keywords_) file_ << ',' << column;
  // Several agents: each one's own return too (r_0, r_1, ...; rlrun's addition, after SB3's
  // columns so that load_results still reads the file).
  for (int a = 0; a < agent_columns(); ++a) file_ << ",r_" << std::to_string(a);
  file_ << '\n';
  file_.flush();
}

Monitor::~Monitor() = default;

void Monitor::write_own_state(StateWriter& out) const {
  StateWriter own = out.sub("monitor");
  own.put_double("episode_return", episode_return_);
  if (agent_columns() > 0) {
    std::vector<double> returns = agent_returns_;
    returns.resize(static_cast<size_t>(agent_columns()), 0.0);
    own.put_vector("agent_returns", returns);
  }
  own.put_int("episode_length", episode_length_);
  own.put_int("total_episodes", total_episodes_);
  own.put_int("total_steps", total_steps_);
  own.put_bool("needs_reset", needs_reset_);
  own.put_double("t_start", t_start_);
}

void Monitor::read_own_state(const StateReader& in) {
  const StateReader own = in.sub("monitor");
  episode_return_ = own.get_double("episode_return");
  if (agent_columns() > 0 && own.has("agent_returns"))
    agent_returns_ = own.get_span<double>("agent_returns", agent_columns());
  episode_length_ = own.get_count("episode_length");
  total_episodes_ = static_cast<int>(own.get_count("total_episodes", INT_MAX));
  total_steps_ = own.get_count("total_steps");
  needs_reset_ = own.get_bool("needs_reset");
  t_start_ = own.get_double("t_start");
  const double since_start =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count() -
      t_start_;
  clock_start_ = std::chrono::steady_clock::now() -
                 std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                     std::chrono::duration<double>(since_start));
}

void Monitor::copy_inner_info() {
  // Keys an env declares after it was built (a Python env learns its info keys from the
  // dicts it returns) are forwarded from then on.
  const auto& keys = inner_->info().keys();
  if (inner_to_own_.size() < keys.size()) {
    for (size_t i = inner_to_own_.size(); i < keys.size(); ++i)
      inner_to_own_.push_back(info_.add_key(keys[i]));
    for (size_t k = 0; k < keywords_.size(); ++k)
      if (keyword_inner_index_[k] < 0) keyword_inner_index_[k] = inner_->info().find(keywords_[k]);
  }
  const auto& values = inner_->info().values();
  for (size_t i = 0; i < inner_to_own_.size(); ++i) info_.set(inner_to_own_[i], values[i]);
  info_.set(episode_r_, Info::kAbsent);
  info_.set(episode_l_, Info::kAbsent);
  info_.set(episode_t_, Info::kAbsent);
  for (int index : keyword_own_index_) info_.set(index, Info::kAbsent);
}

void Monitor::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  inner_->reset(seed, obs);
  copy_inner_info();
  episode_return_ = 0.0;
  std::fill(agent_returns_.begin(), agent_returns_.end(), 0.0);
  episode_length_ = 0;
  needs_reset_ = false;
}

StepResult Monitor::step(std::span<const float> action, std::span<float> obs) {
  require_not_ended();
  const StepResult result = inner_->step(action, obs);
  account(result.reward, result.terminated || result.truncated);
  return result;
}

bool Monitor::steps_asynchronously() const { return asynchronous_steps(*inner_) != nullptr; }

void Monitor::start_step(std::span<const float> action) {
  require_not_ended();
  asynchronous_steps(*inner_)->start_step(action);
}

StepResult Monitor::finish_step(std::span<float> obs) {
  const StepResult result = asynchronous_steps(*inner_)->finish_step(obs);
  account(result.reward, result.terminated || result.truncated);
  return result;
}

// Several agents: the episode's return is the sum of all agents' rewards (PettingZoo's total
// reward), and the episode ends when all agents' do (they end together in rlrun).
void Monitor::step_agents(std::span<const float> actions, std::span<float> obs,
                          std::span<StepResult> results) {
  require_not_ended();
  inner_->step_agents(actions, obs, results);
  account_agents(results);
}

void Monitor::start_step_agents(std::span<const float> actions) {
  require_not_ended();
  asynchronous_steps(*inner_)->start_step_agents(actions);
}

void Monitor::finish_step_agents(std::span<float> obs, std::span<StepResult> results) {
  asynchronous_steps(*inner_)->finish_step_agents(obs, results);
  account_agents(results);
}

void Monitor::account_agents(std::span<const StepResult> results) {
  double reward = 0.0;
  bool ended = true;
  agent_returns_.resize(results.size(), 0.0);
  for (size_t a = 0; a < results.size(); ++a) {
    reward += results[a].reward;
    agent_returns_[a] += results[a].reward;
    ended = ended && (results[a].terminated || results[a].truncated);
  }
  account(reward, ended);
}

void Monitor::require_not_ended() const {
  if (needs_reset_)
    throw RuntimeFailure("Monitor: tried to step " + id() +
                         " after its episode ended; call reset() first (SB3's Monitor rule)");
}

void Monitor::account(double reward, bool episode_ended) {
  copy_inner_info();
  episode_return_ += reward;
  ++episode_length_;
  ++total_steps_;
  if (episode_ended) {
    needs_reset_ = true;
    ++total_episodes_;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start_).count();
    const double r = round6(episode_return_);
    const double t = round6(elapsed);
    info_.set(episode_r_, r);
    info_.set(episode_l_, static_cast<double>(episode_length_));
    info_.set(episode_t_, t);
    const auto& values = inner_->info().values();
    for (size_t k = 0; k < keywords_.size(); ++k)
      if (keyword_inner_index_[k] >= 0)
        info_.set(keyword_own_index_[k], values[keyword_inner_index_[k]]);
    if (file_.is_open()) {
      char length[24];
      std::snprintf(length, sizeof length, ",%lld,", static_cast<long long>(episode_length_));
      file_ << python_float_repr(r) << length << python_float_repr(t);
      for (size_t k = 0; k < keywords_.size(); ++k) {
        const int index = keyword_inner_index_[k];
        const double v = index >= 0 ? values[index] : Info::kAbsent;
        // Flags (is_success, is_failure) as Python writes a bool; every other key a number.
        const bool flag = keywords_[k].rfind("is_", 0) == 0 && (v == 0.0 || v == 1.0);
        if (std::isnan(v))
          file_ << ',';
        else if (flag)
          file_ << (v == 1.0 ? ",True" : ",False");
        else
          file_ << ',' << python_float_repr(v);
      }
      for (int a = 0; a < agent_columns(); ++a)
        file_ << ','
              << python_float_repr(
                     round6(a < static_cast<int>(agent_returns_.size()) ? agent_returns_[a] : 0.0));
      file_ << '\n';
      file_.flush();  // a full disk stops the run here: RuntimeFailure naming the file and errno
    }
  }
}

}  // namespace rlrun
