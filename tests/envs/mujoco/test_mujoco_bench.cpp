// Raw speed of a MuJoCo task: rlrun's Ant-v4 step against plain MuJoCo stepping the same model
// the way Gymnasium's do_simulation does (ctrl, 5 x mj_step, mj_rnePostConstraint), one thread.
// Both follow the same trajectory bit for bit (tests/envs/mujoco/test_ant.cpp): the same random
// actions, and a reset with ant_v4.py's noise from the same seeded stream whenever the ant is
// unhealthy, so they simulate the same contacts. Measured, not asserted (docs/benchmarks.md):
//   build/tests/rlrun_tests "[mujoco_bench]"
#include <mujoco/mujoco.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <vector>

#include "envs/mujoco/mujoco_reference.hpp"
#include "rlrun/envs/mujoco/ant.hpp"
#include "rlrun/rng.hpp"

using namespace rlrun;

namespace {

constexpr int kSteps = 20000;

struct Speed {
  double wall = 0.0;  // env steps per second of wall time
  double cpu = 0.0;   // env steps per second of this process's CPU time
};

Speed measure(const std::function<void()>& one_step) {
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  for (int i = 0; i < kSteps; ++i) one_step();
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  return {kSteps / wall, kSteps / cpu};
}

// The model stepped through MuJoCo's C API alone: what any wrapper of it must pay.
class PlainAnt {
 public:
  PlainAnt(bool rne_post_constraint, const std::vector<float>& actions)
      : rne_post_constraint_(rne_post_constraint), actions_(actions) {
    char error[1024] = "";
    m_ = mj_loadXML(testing::mujoco_model_file("ant.xml").c_str(), nullptr, error, sizeof error);
    REQUIRE(m_);
    d_ = mj_makeData(m_);
    reset();
  }
  ~PlainAnt() {
    mj_deleteData(d_);
    mj_deleteModel(m_);
  }
  PlainAnt(const PlainAnt&) = delete;
  PlainAnt& operator=(const PlainAnt&) = delete;

  void step() {
    for (int j = 0; j < m_->nu; ++j) d_->ctrl[j] = actions_[next_++ % actions_.size()];
    for (int k = 0; k < 5; ++k) mj_step(m_, d_);
    if (rne_post_constraint_) mj_rnePostConstraint(m_, d_);
    bool finite = true;
    for (int i = 0; i < m_->nq; ++i) finite = finite && std::isfinite(d_->qpos[i]);
    for (int i = 0; i < m_->nv; ++i) finite = finite && std::isfinite(d_->qvel[i]);
    if (!finite || d_->qpos[2] < 0.2 || d_->qpos[2] > 1.0) reset();
  }
  const double* qpos() const { return d_->qpos; }

 private:
  void reset() {
    mj_resetData(m_, d_);
    for (int i = 0; i < m_->nq; ++i) d_->qpos[i] = m_->qpos0[i] + rng_.uniform(-0.1, 0.1);
    for (int i = 0; i < m_->nv; ++i) d_->qvel[i] = 0.1 * rng_.normal();
    mj_forward(m_, d_);
  }
  mjModel* m_ = nullptr;
  mjData* d_ = nullptr;
  bool rne_post_constraint_;
  const std::vector<float>& actions_;
  size_t next_ = 0;
  Rng rng_{1};  // as the env's stream after reset(seed 1)
};

}  // namespace

TEST_CASE("bench: Ant-v4 env steps/s against plain MuJoCo", "[.bench][mujoco_bench]") {
  std::vector<float> actions(8 * kSteps);
  Rng draws(7);
  for (float& a : actions) a = static_cast<float>(draws.uniform(-1.0, 1.0));
  PlainAnt plain(true, actions), bare(false, actions);
  mujoco::Ant env;
  std::vector<float> obs(27);
  env.reset(1, obs);
  size_t next = 0;
  const auto rlrun_step = [&] {
    const std::span<const float> action(actions.data() + next % actions.size(), 8);
    next += 8;
    if (env.step(action, obs).terminated) env.reset(std::nullopt, obs);
  };
  // Alternated rounds, the best of each kept: the machine may be shared.
  Speed best_plain, best_bare, best_rlrun;
  const auto keep = [](Speed& best, Speed s) {
    best.wall = std::max(best.wall, s.wall);
    best.cpu = std::max(best.cpu, s.cpu);
  };
  for (int round = 0; round < 5; ++round) {
    keep(best_plain, measure([&] { plain.step(); }));
    keep(best_bare, measure([&] { bare.step(); }));
    keep(best_rlrun, measure(rlrun_step));
  }
  // The same trajectory: after the same number of steps, the same state.
  for (int i = 0; i < 15; ++i) {
    CHECK(env.qpos()[static_cast<size_t>(i)] == plain.qpos()[i]);
    CHECK(bare.qpos()[i] == plain.qpos()[i]);
  }
  std::printf("| run (Ant, frame_skip 5, one thread) | steps/s (wall) | steps/s (CPU) |\n");
  std::printf("|---|---|---|\n");
  std::printf("| plain MuJoCo: ctrl, 5 x mj_step | %.0f | %.0f |\n", best_bare.wall, best_bare.cpu);
  std::printf("| plain MuJoCo: ctrl, 5 x mj_step, mj_rnePostConstraint | %.0f | %.0f |\n",
              best_plain.wall, best_plain.cpu);
  std::printf("| rlrun Ant-v4 step | %.0f | %.0f |\n", best_rlrun.wall, best_rlrun.cpu);
  std::printf("rlrun / plain (with mj_rnePostConstraint), CPU: %.1f %%\n",
              100.0 * best_rlrun.cpu / best_plain.cpu);
}
