#include "rlrun/env/action_mask.hpp"

#include <algorithm>

#include "rlrun/core/errors.hpp"
#include "rlrun/env/vec_env.hpp"

namespace rlrun {

namespace {
constexpr const char* kPrefix = "action_mask.";

// The categorical parts a mask splits into (sb3-contrib: one MaskableCategorical each).
std::vector<int64_t> mask_parts(const Space& space) {
  switch (space.kind()) {
    case SpaceKind::kDiscrete: return {space.n()};
    case SpaceKind::kMultiDiscrete: return space.nvec();
    case SpaceKind::kMultiBinary: return std::vector<int64_t>(static_cast<size_t>(space.n()), 2);
    case SpaceKind::kBox:
    case SpaceKind::kDict: break;
  }
  return {};
}

// Entries the Info holds under action_mask.<k> with a value (for the wrong-length message).
int reported_entries(const Info& info) {
  int count = 0;
  const std::vector<std::string>& keys = info.keys();
  for (size_t i = 0; i < keys.size(); ++i)
    if (keys[i].rfind(kPrefix, 0) == 0 && info.has(static_cast<int>(i))) ++count;
  return count;
}
}  // namespace

std::string action_mask_key(int index) { return kPrefix + std::to_string(index); }

int action_mask_size(const Space& action_space) {
  int64_t total = 0;
  for (int64_t n : mask_parts(action_space)) total += n;
  return static_cast<int>(total);
}

std::string action_mask_problem(const Space& action_space, std::span<const float> mask) {
  const std::vector<int64_t> parts = mask_parts(action_space);
  size_t at = 0;
  for (size_t part = 0; part < parts.size(); ++part) {
    bool legal = false;
    for (int64_t i = 0; i < parts[part]; ++i, ++at) {
      const float value = mask[at];
      if (value != 0.0f && value != 1.0f)
        return "action mask entry " + std::to_string(at) + " is " + std::to_string(value) +
               ", not 0 or 1";
      legal = legal || value == 1.0f;
    }
    if (!legal)
      return parts.size() == 1 ? "the action mask allows no action (every entry is 0)"
                               : "the action mask allows no value of action entry " +
                                     std::to_string(part) + " (of " + action_space.describe() + ")";
  }
  return "";
}

ActionMaskReader::ActionMaskReader(const Space& action_space)
    : action_space_(action_space), size_(action_mask_size(action_space)) {}

void ActionMaskReader::resolve(const Info& info, int total) {
  indices_.resize(static_cast<size_t>(total));
  for (int k = 0; k < total; ++k) indices_[k] = info.find(action_mask_key(k));
  beyond_ = info.find(action_mask_key(total));
  known_keys_ = info.keys().size();
}

std::string ActionMaskReader::read(const Info& info, int agents, std::span<float> out) {
  const int total = agents * size_;
  if (static_cast<int>(indices_.size()) != total || info.keys().size() != known_keys_)
    resolve(info, total);
  const bool missing =
      std::any_of(indices_.begin(), indices_.end(), [&](int index) { return !info.has(index); });
  if (missing || info.has(beyond_)) {
    const int reported = reported_entries(info);
    const std::string needed = std::to_string(total) + " (" + action_space_.describe() +
                               (agents > 1 ? ", " + std::to_string(agents) + " agents" : "") + ")";
    if (reported == 0)
      return "the env reports no action mask (info action_mask.0, ...), which MaskablePPO "
             "needs; its entries must number " +
             needed;
    return "the env reports an action mask of " + std::to_string(reported) +
           " entries, MaskablePPO needs " + needed;
  }
  for (int k = 0; k < total; ++k) out[k] = static_cast<float>(info.get(indices_[k]));
  for (int a = 0; a < agents; ++a) {
    std::string problem =
        action_mask_problem(action_space_, out.subspan(static_cast<size_t>(a) * size_, size_));
    if (!problem.empty())
      return agents > 1 ? "agent " + std::to_string(a) + ": " + problem : problem;
  }
  return "";
}

void read_action_masks(const VecEnv& env, std::vector<ActionMaskReader>& readers,
                       Eigen::MatrixXf& masks, int64_t step) {
  if (readers.empty()) readers.assign(env.num_copies(), ActionMaskReader(env.action_space()));
  const int size = readers.front().size();
  masks.resize(size, env.num_envs());
  int column = 0;
  for (int c = 0; c < env.num_copies(); ++c) {
    const Env& copy = env.env(c);
    const int agents = copy.num_agents();
    const std::string problem = readers[c].read(
        copy.info(), agents,
        std::span<float>(masks.col(column).data(), static_cast<size_t>(size) * agents));
    if (!problem.empty())
      throw RuntimeFailure(copy.id() + " (env " + std::to_string(c) + ") " +
                           (step < 0 ? "after reset()" : "at step " + std::to_string(step)) + ": " +
                           problem);
    column += agents;
  }
}

}  // namespace rlrun
