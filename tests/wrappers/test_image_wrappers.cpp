// AddRenderObservation and GrayscaleObservation (Gymnasium 1.0's image wrappers): the pixels are
// the env's own rendering of its current state, the layouts and spaces Gymnasium's, and gray
// values the ones numpy computes (expected values printed by numpy 1.24:
// np.sum(np.multiply(np.array(px, dtype=np.uint8), [0.2125, 0.7154, 0.0721]), axis=-1)
// .astype(np.uint8)).
#include <catch2/catch.hpp>
#include <memory>
#include <stdexcept>
#include <vector>

#include "rlrun/envs/classic/cartpole.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/wrappers/add_render_observation.hpp"
#include "rlrun/wrappers/grayscale_observation.hpp"
#include "scripted_env.hpp"

namespace rlrun {
namespace {

// CartPole seeded as the wrapped one, drawn at width x height: the frame the wrapper must
// observe after the same reset and actions.
std::vector<float> drawn(uint64_t seed, const std::vector<float>& actions, int width, int height) {
  CartPole env;
  std::vector<float> obs(4);
  env.reset(seed, obs);
  for (float a : actions) env.step(std::vector<float>{a}, obs);
  Frame frame(width, height);
  REQUIRE(env.render(frame));
  std::vector<uint8_t> rgb;
  frame.to_rgb(rgb);
  return {rgb.begin(), rgb.end()};
}

}  // namespace

TEST_CASE("AddRenderObservation observes the env's own frame after every reset and step",
          "[wrappers][image]") {
  AddRenderObservation::Config config;
  config.width = 84;
  config.height = 64;
  AddRenderObservation env(std::make_unique<CartPole>(), config);
  REQUIRE(env.observation_space().is_box());
  CHECK(env.observation_space().shape() == std::vector<int>{64, 84, 3});
  CHECK(env.observation_space().low().front() == 0.0f);
  CHECK(env.observation_space().high().front() == 255.0f);
  std::vector<float> obs(static_cast<size_t>(env.observation_space().flat_dim()));
  env.reset(7, obs);
  CHECK(obs == drawn(7, {}, 84, 64));
  std::vector<float> actions;
  for (int t = 0; t < 5; ++t) {
    actions.push_back(static_cast<float>(t % 2));
    env.step(std::vector<float>{actions.back()}, obs);
  }
  CHECK(obs == drawn(7, actions, 84, 64));
  // Not a blank picture: the cart and pole are drawn on the white background.
  CHECK(std::count(obs.begin(), obs.end(), 255.0f) < static_cast<long>(obs.size()));
  // Gymnasium's size when none is given: CartPole's 600x400.
  AddRenderObservation full(std::make_unique<CartPole>());
  CHECK(full.observation_space().shape() == std::vector<int>{400, 600, 3});
}

TEST_CASE("AddRenderObservation with render_only false keeps the state beside the frame",
          "[wrappers][image]") {
  AddRenderObservation::Config config;
  config.render_only = false;
  config.width = config.height = 40;
  AddRenderObservation env(std::make_unique<CartPole>(), config);
  const Space& space = env.observation_space();
  REQUIRE(space.is_dict());
  CHECK(space.keys() == std::vector<std::string>{"pixels", "state"});  // sorted, as Gymnasium
  std::vector<float> obs(static_cast<size_t>(space.flat_dim()));
  env.reset(3, obs);
  CartPole plain;
  std::vector<float> state(4);
  plain.reset(3, state);
  CHECK(std::vector<float>(obs.begin() + space.offset(1), obs.end()) == state);
  const std::vector<float> pixels(obs.begin(), obs.begin() + space.offset(1));
  CHECK(pixels == drawn(3, {}, 40, 40));

  config.obs_key = config.render_key;
  CHECK_THROWS_WITH(AddRenderObservation(std::make_unique<CartPole>(), config),
                    Catch::Contains("two different"));
  CHECK_THROWS_WITH(AddRenderObservation(std::make_unique<testing::ScriptedEnv>(
                        std::vector<std::vector<float>>{{0.0f}},
                        std::vector<std::vector<float>>{{0.0f}}, std::vector<double>{0.0}, 5)),
                    Catch::Contains("cannot render"));
}

TEST_CASE("GrayscaleObservation gives numpy's gray values", "[wrappers][image]") {
  CHECK(GrayscaleObservation::gray(255, 255, 255) == 255.0f);
  CHECK(GrayscaleObservation::gray(0, 0, 0) == 0.0f);
  CHECK(GrayscaleObservation::gray(1, 2, 3) == 1.0f);
  CHECK(GrayscaleObservation::gray(100, 150, 200) == 142.0f);
  CHECK(GrayscaleObservation::gray(254, 1, 77) == 60.0f);
  CHECK(GrayscaleObservation::gray(37, 211, 9) == 159.0f);
  CHECK(GrayscaleObservation::gray(128, 128, 128) == 128.0f);

  AddRenderObservation::Config pixels;
  pixels.width = pixels.height = 48;
  for (bool keep_dim : {false, true}) {
    GrayscaleObservation::Config config;
    config.keep_dim = keep_dim;
    GrayscaleObservation env(
        std::make_unique<AddRenderObservation>(std::make_unique<CartPole>(), pixels), config);
    CHECK(env.observation_space().shape() ==
          (keep_dim ? std::vector<int>{48, 48, 1} : std::vector<int>{48, 48}));
    std::vector<float> obs(48 * 48);
    env.reset(11, obs);
    const std::vector<float> rgb = drawn(11, {}, 48, 48);
    for (size_t p = 0; p < obs.size(); ++p)
      REQUIRE(obs[p] == GrayscaleObservation::gray(rgb[3 * p], rgb[3 * p + 1], rgb[3 * p + 2]));
  }
  CHECK_THROWS_WITH(GrayscaleObservation(std::make_unique<CartPole>()),
                    Catch::Contains("needs an RGB image observation"));
}

}  // namespace rlrun
