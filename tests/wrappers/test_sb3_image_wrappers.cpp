// The image preprocessing of Gymnasium 0.29 / rl-zoo / SB3's atari_wrappers.py, on an env whose
// frames are known: ResizeObservation (OpenCV's INTER_AREA, itself checked against cv2 in
// test_opencv_image_ops.cpp), GrayscaleObservation's OpenCV weights, FrameSkip and MaxAndSkip
// (SB3's loop: the max of the last two frames, the buffer kept across steps), NoopReset,
// TransformReward's sign (np.sign), and FrameStack's SB3 layout (np.concatenate on the channel
// axis), each expectation written from the Python code's definition, not from rlrun's.
#include <catch2/catch.hpp>
#include <memory>
#include <set>
#include <stdexcept>
#include <vector>

#include "rlrun/state.hpp"
#include "rlrun/wrappers/action_repeat.hpp"
#include "rlrun/wrappers/frame_stack.hpp"
#include "rlrun/wrappers/grayscale_observation.hpp"
#include "rlrun/wrappers/noop_reset.hpp"
#include "rlrun/wrappers/opencv_image_ops.hpp"
#include "rlrun/wrappers/resize_observation.hpp"
#include "rlrun/wrappers/transform_reward.hpp"
#include "scripted_env.hpp"

namespace rlrun {
namespace {

// Frames of `shape` (values 0-255) that depend on the env step count t: pixel i of step t is
// (37 t + 11 i + 5 * resets) mod 256; reward t - 2 at step t; episodes end after `length` steps.
// Actions are Discrete(3); every action taken is recorded.
class PixelEnv : public Env {
 public:
  PixelEnv(std::vector<int> shape, int length)
      : space_(Space::image(shape)), actions_(Space::discrete(3)), length_(length) {}
  const Space& observation_space() const override { return space_; }
  const Space& action_space() const override { return actions_; }
  void reset(std::optional<uint64_t>, std::span<float> obs) override {
    ++resets;
    episode_steps = 0;
    draw(obs);
  }
  StepResult step(std::span<const float> action, std::span<float> obs) override {
    taken.push_back(action[0]);
    ++t;
    ++episode_steps;
    draw(obs);
    return {static_cast<double>(t) - 2.0, episode_steps >= length_, false};
  }
  const Info& info() const override { return info_; }
  std::string id() const override { return "Pixels-v0"; }
  // Its frames follow from t alone: nothing of its own to save (the wrappers' state is tested).
  bool can_save_state() const override { return true; }
  void write_state(StateWriter&) const override {}
  void read_state(const StateReader&) override {}
  static float pixel(int t, int i, int resets) {
    return static_cast<float>((37 * t + 11 * i + 5 * resets) % 256);
  }
  std::vector<float> frame() const {
    std::vector<float> f(static_cast<size_t>(space_.flat_dim()));
    draw(f);
    return f;
  }

  int t = 0, resets = 0, episode_steps = 0;
  std::vector<float> taken;

 private:
  void draw(std::span<float> obs) const {
    for (size_t i = 0; i < obs.size(); ++i) obs[i] = pixel(t, static_cast<int>(i), resets);
  }
  Space space_, actions_;
  int length_;
  Info info_;
};

struct Stack {
  PixelEnv* env;
  EnvPtr top;
};
template <class W, class... Args>
Stack wrapped(std::vector<int> shape, int length, Args&&... args) {
  auto env = std::make_unique<PixelEnv>(std::move(shape), length);
  PixelEnv* raw = env.get();
  return {raw, std::make_unique<W>(std::move(env), std::forward<Args>(args)...)};
}

}  // namespace

TEST_CASE("ResizeObservation: OpenCV's INTER_AREA of every frame, channel axis kept",
          "[wrappers][image]") {
  ResizeObservation::Config config;
  config.shape = {64, 48};
  auto [env, top] = wrapped<ResizeObservation>({96, 96, 3}, 100, config);
  CHECK(top->observation_space().shape() == std::vector<int>{64, 48, 3});
  std::vector<float> obs(64 * 48 * 3);
  auto expected = [&] {
    const std::vector<float> frame = env->frame();
    std::vector<uint8_t> src(frame.begin(), frame.end()), dst(obs.size());
    opencv_area_resize(src, {96, 96, 3}, 64, 48, dst);
    return std::vector<float>(dst.begin(), dst.end());
  };
  top->reset(1, obs);
  CHECK(obs == expected());
  top->step(std::vector<float>{1}, obs);
  CHECK(obs == expected());
  // A gray (height, width) image stays two-dimensional; one number is a square.
  config.shape = {32, 32};
  auto [gray_env, gray] = wrapped<ResizeObservation>({96, 96}, 100, config);
  CHECK(gray->observation_space().shape() == std::vector<int>{32, 32});
  // Refused: growing, a non-image, more than 4 channels at a fractional factor.
  config.shape = {100, 96};
  CHECK_THROWS_WITH(wrapped<ResizeObservation>({96, 96, 3}, 10, config),
                    Catch::Contains("only shrinks"));
  config.shape = {64, 64};
  CHECK_THROWS_WITH(wrapped<ResizeObservation>({96, 96, 8}, 10, config),
                    Catch::Contains("cn <= 4"));
  CHECK_THROWS_WITH(wrapped<ResizeObservation>({96}, 10, config),
                    Catch::Contains("needs an image observation"));
}

TEST_CASE("GrayscaleObservation with OpenCV's weights (Gymnasium 0.29, SB3 WarpFrame)",
          "[wrappers][image]") {
  GrayscaleObservation::Config config;
  config.weights = "opencv";
  config.keep_dim = true;
  auto [env, top] = wrapped<GrayscaleObservation>({5, 4, 3}, 100, config);
  CHECK(top->observation_space().shape() == std::vector<int>{5, 4, 1});
  std::vector<float> obs(20);
  top->reset(1, obs);
  const std::vector<float> rgb = env->frame();
  for (int p = 0; p < 20; ++p) {
    // cv2 COLOR_RGB2GRAY: round(0.299 r + 0.587 g + 0.114 b) in 15-bit fixed point.
    const int r = static_cast<int>(rgb[3 * p]), g = static_cast<int>(rgb[3 * p + 1]),
              b = static_cast<int>(rgb[3 * p + 2]);
    CHECK(obs[p] == static_cast<float>((9798 * r + 19235 * g + 3735 * b + 16384) >> 15));
  }
  config.weights = "rec709";
  CHECK_THROWS_WITH(wrapped<GrayscaleObservation>({5, 4, 3}, 10, config),
                    Catch::Contains("weights"));
}

TEST_CASE("FrameSkip and MaxAndSkip repeat the action and sum the rewards as rl-zoo and SB3",
          "[wrappers][image]") {
  SECTION("FrameSkip: the last frame") {
    auto [env, top] = wrapped<FrameSkip>({2, 2, 1}, 100, FrameSkip::Config{3});
    std::vector<float> obs(4);
    top->reset(1, obs);
    const StepResult r = top->step(std::vector<float>{2}, obs);
    CHECK(env->taken == std::vector<float>{2, 2, 2});
    CHECK(r.reward == (1 - 2) + (2 - 2) + (3 - 2));
    CHECK(obs == env->frame());
  }
  SECTION("MaxAndSkip: the max of the last two frames; the buffer outlives episodes") {
    auto [env, top] = wrapped<MaxAndSkip>({2, 2, 1}, 5, MaxAndSkip::Config{4});
    std::vector<float> obs(4);
    top->reset(1, obs);  // resets = 1
    StepResult r = top->step(std::vector<float>{1}, obs);
    CHECK(env->t == 4);
    CHECK(r.reward == -1 + 0 + 1 + 2);
    for (int i = 0; i < 4; ++i)
      CHECK(obs[i] == std::max(PixelEnv::pixel(3, i, 1), PixelEnv::pixel(4, i, 1)));
    // Step 5 ends the episode at its first repeat: SB3 writes neither buffer slot, so the max
    // is still that of steps 3 and 4.
    r = top->step(std::vector<float>{0}, obs);
    CHECK(env->t == 5);
    CHECK(r.terminated);
    CHECK(r.reward == 3);
    for (int i = 0; i < 4; ++i)
      CHECK(obs[i] == std::max(PixelEnv::pixel(3, i, 1), PixelEnv::pixel(4, i, 1)));
    // The buffer is part of the state (exact resume).
    TensorMap tensors;
    StateWriter writer(tensors);
    top->write_state(writer);
    CHECK(tensors.count("action_repeat/last_two") == 1);
  }
  CHECK_THROWS_WITH(
      MaxAndSkip(std::make_unique<PixelEnv>(std::vector<int>{2}, 5), MaxAndSkip::Config{0}),
      Catch::Contains("skip must be >= 1"));
}

TEST_CASE("NoopReset: 1 to noop_max steps of action 0 after reset, reseeded by the seed",
          "[wrappers][image]") {
  NoopReset::Config config;
  config.noop_max = 7;
  std::vector<int> counts;
  for (uint64_t seed : {1, 2, 3, 4, 5, 6, 7, 8, 1}) {
    auto [env, top] = wrapped<NoopReset>({3}, 1000, config);
    std::vector<float> obs(3);
    top->reset(seed, obs);
    const int noops = env->t;
    CHECK(noops >= 1);
    CHECK(noops <= 7);
    CHECK(env->taken == std::vector<float>(static_cast<size_t>(noops), 0.0f));
    CHECK(obs == env->frame());
    counts.push_back(noops);
  }
  CHECK(counts.front() == counts.back());  // the same seed, the same count
  CHECK(std::set<int>(counts.begin(), counts.end()).size() > 1);
  // An episode that ends during the no-ops is reset again (SB3), here after every step.
  auto [short_env, short_top] = wrapped<NoopReset>({3}, 1, config);
  std::vector<float> obs(3);
  short_top->reset(9, obs);
  CHECK(short_env->resets == 1 + short_env->t);
  // Only a Discrete action space that holds 0.
  CHECK_THROWS_WITH(NoopReset(std::make_unique<testing::ScriptedEnv>(
                        std::vector<std::vector<float>>{{0}}, std::vector<std::vector<float>>{{0}},
                        std::vector<double>{0}, 5)),
                    Catch::Contains("Discrete action space holding action 0"));
}

TEST_CASE("TransformReward sign: np.sign of the reward (SB3 ClipRewardEnv)", "[wrappers]") {
  TransformReward::Config config;
  config.sign = true;
  auto [env, top] = wrapped<TransformReward>({1}, 100, config);
  std::vector<float> obs(1);
  top->reset(1, obs);
  std::vector<double> rewards;
  for (int i = 0; i < 4; ++i) rewards.push_back(top->step(std::vector<float>{0}, obs).reward);
  CHECK(rewards == std::vector<double>{-1, 0, 1, 1});  // env rewards -1, 0, 1, 2
}

TEST_CASE("FrameStack layout sb3: SB3 VecFrameStack's np.concatenate on the channel axis",
          "[wrappers][image]") {
  FrameStack::Config config;
  config.n_stack = 3;
  config.layout = "sb3";
  SECTION("channels-last image: (H, W, C) -> (H, W, n C), frame k at channels [k C, (k+1) C)") {
    auto [env, top] = wrapped<FrameStack>({4, 5, 2}, 100, config);
    CHECK(top->observation_space().shape() == std::vector<int>{4, 5, 6});
    std::vector<float> obs(4 * 5 * 6);
    top->reset(1, obs);
    for (int s = 0; s < 2; ++s) top->step(std::vector<float>{0}, obs);
    // Frames: reset (t 0), steps t 1 and 2, one env of resets = 1.
    for (int hw = 0; hw < 20; ++hw)
      for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 2; ++c)
          CHECK(obs[hw * 6 + k * 2 + c] == PixelEnv::pixel(k, hw * 2 + c, 1));
  }
  SECTION("channels-first image: (C, H, W) -> (n C, H, W), frames one after another") {
    auto [env, top] = wrapped<FrameStack>({1, 6, 7}, 100, config);
    CHECK(top->observation_space().shape() == std::vector<int>{3, 6, 7});
    std::vector<float> obs(3 * 42);
    top->reset(1, obs);
    // Zero padding before the first frame (VecFrameStack).
    for (int i = 0; i < 84; ++i) CHECK(obs[i] == 0.0f);
    for (int i = 0; i < 42; ++i) CHECK(obs[84 + i] == PixelEnv::pixel(0, i, 1));
  }
  SECTION("a vector stacks on its last axis: (d,) -> (n d,)") {
    auto [env, top] = wrapped<FrameStack>({4}, 100, config);
    CHECK(top->observation_space().shape() == std::vector<int>{12});
  }
  SECTION("Gymnasium's FrameStackObservation: a new leading axis, copies of the first frame") {
    auto [env, top] =
        wrapped<FrameStackObservation>({2, 3}, 100, FrameStackObservation::Config{3, "reset"});
    CHECK(top->observation_space().shape() == std::vector<int>{3, 2, 3});
    std::vector<float> obs(18);
    top->reset(1, obs);
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 6; ++i) CHECK(obs[k * 6 + i] == PixelEnv::pixel(0, i, 1));
  }
  SECTION("channels_order last on a channels-first-looking image") {
    config.channels_order = "last";
    auto [env, top] = wrapped<FrameStack>({1, 6, 7}, 100, config);
    CHECK(top->observation_space().shape() == std::vector<int>{1, 6, 21});
  }
}

}  // namespace rlrun
