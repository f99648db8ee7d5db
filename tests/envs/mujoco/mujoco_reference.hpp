#pragma once
// The tests' own MuJoCo: a model loaded and stepped through MuJoCo's C API directly, the way
// Gymnasium's MujocoEnv drives it (set_state = qpos, qvel, mj_forward; do_simulation = ctrl,
// frame_skip mj_step, mj_rnePostConstraint), without rlrun's env code. A task's test computes
// the task's observation and reward from this simulation by its own formula and compares.
#include <mujoco/mujoco.h>

#include <catch2/catch.hpp>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "test_paths.hpp"

namespace rlrun::testing {

// scenarios/mujoco/<file> of this checkout.
inline std::string mujoco_model_file(const std::string& file) {
  return std::string(test_paths::source_dir()) + "/scenarios/mujoco/" + file;
}

// FNV-1a (64 bit) of the binary model (mj_saveModel): scripts/data/make_mujoco_model_hashes.sh
// computes the same of Gymnasium's assets.
inline uint64_t mujoco_model_hash(const mjModel& m) {
  std::vector<unsigned char> bytes(static_cast<size_t>(mj_sizeModel(&m)));
  mj_saveModel(&m, nullptr, bytes.data(), static_cast<int>(bytes.size()));
  uint64_t hash = 14695981039346656037ull;
  for (unsigned char b : bytes) {
    hash ^= b;
    hash *= 1099511628211ull;
  }
  return hash;
}

class ReferenceSim {
 public:
  explicit ReferenceSim(const std::string& file) {
    char error[1024] = "";
    model_ = mj_loadXML(mujoco_model_file(file).c_str(), nullptr, error, sizeof error);
    INFO(error);
    REQUIRE(model_ != nullptr);
    data_ = mj_makeData(model_);
  }
  ~ReferenceSim() {
    mj_deleteData(data_);
    mj_deleteModel(model_);
  }
  ReferenceSim(const ReferenceSim&) = delete;
  ReferenceSim& operator=(const ReferenceSim&) = delete;

  void set_state(std::span<const double> qpos, std::span<const double> qvel) {
    REQUIRE(qpos.size() == static_cast<size_t>(model_->nq));
    REQUIRE(qvel.size() == static_cast<size_t>(model_->nv));
    for (int i = 0; i < model_->nq; ++i) data_->qpos[i] = qpos[static_cast<size_t>(i)];
    for (int i = 0; i < model_->nv; ++i) data_->qvel[i] = qvel[static_cast<size_t>(i)];
    mj_forward(model_, data_);
  }
  void step(std::span<const float> action, int frame_skip) {
    for (int i = 0; i < model_->nu; ++i) data_->ctrl[i] = action[static_cast<size_t>(i)];
    for (int i = 0; i < frame_skip; ++i) mj_step(model_, data_);
    mj_rnePostConstraint(model_, data_);
  }
  const mjModel& model() const { return *model_; }
  const mjData& data() const { return *data_; }
  std::vector<double> qpos() const { return {data_->qpos, data_->qpos + model_->nq}; }
  std::vector<double> qvel() const { return {data_->qvel, data_->qvel + model_->nv}; }
  int body(const char* name) const { return mj_name2id(model_, mjOBJ_BODY, name); }

 private:
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
};

}  // namespace rlrun::testing
