// The five classic-control pictures, checked against the geometry of Gymnasium's render()
// code (gymnasium/envs/classic_control/*.py): where the cart, pole, rod, car, flag and links
// must be for a given state, their colours, and that drawing from an observation gives the
// same picture as drawing the state.
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "render/rgb_print.hpp"
#include "rlrun/envs/classic/acrobot.hpp"
#include "rlrun/envs/classic/cartpole.hpp"
#include "rlrun/envs/classic/mountain_car.hpp"
#include "rlrun/envs/classic/mountain_car_continuous.hpp"
#include "rlrun/envs/classic/pendulum.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/wrappers/time_limit.hpp"

using rlrun::ClassicControlEnv;
using rlrun::Frame;
using rlrun::Rgb;

namespace {

const Rgb kWhite{255, 255, 255};
const Rgb kBlack{0, 0, 0};

// Sets `state`, renders at the env's own size.
Frame draw(ClassicControlEnv& env, std::vector<double> state) {
  std::vector<float> obs(env.observation_space().flat_dim());
  env.reset(1, obs);
  env.set_state(state, obs);
  const rlrun::RenderSpec spec = env.render_spec();
  Frame frame(spec.width, spec.height);
  REQUIRE(env.render(frame));
  return frame;
}

// Mean absolute channel difference of two frames of the same size.
double difference(const Frame& a, const Frame& b) {
  std::vector<uint8_t> x, y;
  a.to_rgb(x);
  b.to_rgb(y);
  double sum = 0;
  for (size_t i = 0; i < x.size(); ++i) sum += std::abs(int(x[i]) - int(y[i]));
  return sum / static_cast<double>(x.size());
}

}  // namespace

TEST_CASE("Classic envs report Gymnasium's frame sizes and fps", "[render]") {
  CHECK(rlrun::CartPole().render_spec().width == 600);
  CHECK(rlrun::CartPole().render_spec().height == 400);
  CHECK(rlrun::CartPole().render_spec().fps == 50);
  CHECK(rlrun::Pendulum().render_spec().width == 500);
  CHECK(rlrun::Pendulum().render_spec().fps == 30);
  CHECK(rlrun::MountainCar().render_spec().width == 600);
  CHECK(rlrun::MountainCarContinuous().render_spec().height == 400);
  CHECK(rlrun::Acrobot().render_spec().width == 500);
  CHECK(rlrun::Acrobot().render_spec().fps == 15);
}

TEST_CASE("Classic envs refuse to render before reset, and wrappers forward render", "[render]") {
  rlrun::CartPole env;
  Frame frame(600, 400);
  CHECK_THROWS_AS(env.render(frame), std::logic_error);
  rlrun::TimeLimit wrapped(std::make_unique<rlrun::CartPole>(), 500);
  std::vector<float> obs(4);
  wrapped.reset(3, obs);
  CHECK(wrapped.render_spec().width == 600);
  CHECK(wrapped.render(frame));
  CHECK(wrapped.render_observation(obs, frame));
}

TEST_CASE("CartPole picture: cart on the track at carty = 100, pole leaning with theta",
          "[render]") {
  rlrun::CartPole env;
  Frame upright = draw(env, {0, 0, 0, 0});
  // Cart: 50x30 black box centred at (300, 100) in y-up coordinates = row 300 from the top.
  CHECK(upright.pixel(300, 310) == kBlack);
  CHECK(upright.pixel(280, 290) == kBlack);
  CHECK(upright.pixel(330, 299) == kBlack);  // the track: pixel row 100 from the bottom
  CHECK(upright.pixel(340, 310) == kWhite);
  // Pole: 10 px wide, from the axle (7.5 above the cart centre) up 120 px: rows ~173-292.
  CHECK(upright.pixel(300, 200) == Rgb{202, 152, 101});
  CHECK(upright.pixel(300, 160) == kWhite);
  // Axle: a blue-grey circle of radius 5 at (300, 107).
  CHECK(upright.pixel(300, 292) == Rgb{129, 132, 203});

  // x = 1.2 moves the cart 150 px right; theta = 0.2 leans the pole right.
  Frame moved = draw(env, {1.2, 0, 0.2, 0});
  CHECK(moved.pixel(450, 310) == kBlack);
  CHECK(moved.pixel(300, 310) == kWhite);
  const double top_x = 450 + 115 * std::sin(0.2), top_y = 400 - (107.5 + 115 * std::cos(0.2));
  CHECK(moved.pixel(int(top_x), int(top_y)) == Rgb{202, 152, 101});
}

TEST_CASE("Pendulum picture: rod from the centre, pointing up at theta = 0", "[render]") {
  rlrun::Pendulum env;
  const Rgb rod{204, 77, 77};
  Frame up = draw(env, {0, 0});
  const double scale = 500 / 4.4;
  CHECK(up.pixel(250, int(250 - 0.5 * scale)) == rod);
  CHECK(up.pixel(250, int(250 + 0.5 * scale)) == kWhite);
  CHECK(up.pixel(250, 250) == kBlack);  // the axle
  // theta = pi/2 is counter-clockwise: the rod points left.
  Frame left = draw(env, {std::numbers::pi / 2, 0});
  CHECK(left.pixel(int(250 - 0.5 * scale), 250) == rod);
  CHECK(left.pixel(int(250 + 0.5 * scale), 250) == kWhite);
}

TEST_CASE("Pendulum draws the torque arrow after a step, only then", "[render]") {
  rlrun::Pendulum env;
  std::vector<float> obs(3);
  env.reset(5, obs);
  Frame before(500, 500), after(500, 500), from_obs(500, 500);
  env.render(before);
  const float torque[] = {2.0f};
  env.step(torque, obs);
  env.render(after);
  env.render_observation(obs, from_obs);
  // The arrow (black, around the axle) appears only in the live render.
  auto dark_pixels = [](const Frame& f) {
    int n = 0;
    for (int y = 180; y < 320; ++y)
      for (int x = 180; x < 320; ++x) n += f.pixel(x, y).r < 60 && f.pixel(x, y).g < 60;
    return n;
  };
  CHECK(dark_pixels(after) > dark_pixels(before) + 200);
  CHECK(dark_pixels(from_obs) < dark_pixels(after));
}

TEST_CASE("MountainCar pictures: hill, car on the hill, flag at the goal", "[render]") {
  const double scale = 600 / 1.8;
  auto height = [](double x) { return std::sin(3 * x) * 0.45 + 0.55; };
  for (double goal : {0.5, 0.45}) {
    std::unique_ptr<ClassicControlEnv> env;
    if (goal == 0.5)
      env = std::make_unique<rlrun::MountainCar>();
    else
      env = std::make_unique<rlrun::MountainCarContinuous>();
    const double pos = -0.5;
    Frame frame = draw(*env, {pos, 0});
    // Car body: 10 px above the hill, 20 px tall; its centre is ~20 px above the curve.
    const double cx = (pos + 1.2) * scale;
    const double cy = 400 - (10 + height(pos) * scale + 10);
    CHECK(frame.pixel(int(cx), int(cy)) == kBlack);
    // Flag pennant (yellow) right of the pole at the goal, 40-50 px above the hill.
    const int flag_x = int((goal + 1.2) * scale);
    const int flag_y = int(height(goal) * scale) + 45;
    CHECK(frame.pixel(flag_x + 5, 400 - flag_y) == Rgb{204, 204, 0});
    // The hill line passes through the bottom of the valley (x = -pi/6, height 0.1).
    const double valley_x = (-std::numbers::pi / 6 + 1.2) * scale;
    bool line = false;
    for (int dy = -2; dy <= 2; ++dy)
      line |= frame.pixel(int(valley_x), int(400 - 0.1 * scale) + dy).r < 128;
    CHECK(line);
  }
}

TEST_CASE("Acrobot picture: links hang down at rest, goal line above", "[render]") {
  rlrun::Acrobot env;
  Frame frame = draw(env, {0, 0, 0, 0});
  const double scale = 500 / 4.4;
  const Rgb cyan{0, 204, 204}, yellow{204, 204, 0};
  CHECK(frame.pixel(250, 250) == yellow);                   // pivot joint
  CHECK(frame.pixel(250, int(250 + 0.5 * scale)) == cyan);  // first link, below the pivot
  CHECK(frame.pixel(250, int(250 + scale)) == yellow);      // elbow joint
  CHECK(frame.pixel(250, int(250 + 1.5 * scale)) == cyan);  // second link
  CHECK(frame.pixel(250, int(250 - 0.5 * scale)) == kWhite);
  CHECK(frame.pixel(20, 500 - 1 - int(250 + scale)) == kBlack);  // goal line, 1 link above
}

TEST_CASE("Drawing from an observation matches drawing the state", "[render]") {
  std::vector<std::unique_ptr<ClassicControlEnv>> envs;
  envs.push_back(std::make_unique<rlrun::CartPole>());
  envs.push_back(std::make_unique<rlrun::Pendulum>());
  envs.push_back(std::make_unique<rlrun::MountainCar>());
  envs.push_back(std::make_unique<rlrun::MountainCarContinuous>());
  envs.push_back(std::make_unique<rlrun::Acrobot>());
  for (auto& env : envs) {
    INFO(env->id());
    std::vector<float> obs(env->observation_space().flat_dim());
    env->reset(11, obs);
    const rlrun::RenderSpec spec = env->render_spec();
    Frame a(spec.width, spec.height), b(spec.width, spec.height);
    env->render(a);
    env->render_observation(obs, b);
    CHECK(difference(a, b) < 0.05);  // float32 rounding of the state moves edges by < 1 px
    const std::vector<float> wrong(obs.size() + 1);
    CHECK_THROWS_AS(env->render_observation(wrong, b), std::invalid_argument);
  }
}

TEST_CASE("Frames of any size show the same scene", "[render]") {
  rlrun::CartPole env;
  std::vector<float> obs(4);
  env.reset(2, obs);
  Frame small(300, 200), wide(800, 400);
  env.render(small);
  env.render(wide);
  CHECK(small.pixel(150, 155) == kBlack);  // cart, scaled by 1/2
  CHECK(wide.pixel(400, 310) == kBlack);   // cart, centred with 100 px margins
  CHECK(wide.pixel(50, 300) == kWhite);    // the margin has no track line
}
