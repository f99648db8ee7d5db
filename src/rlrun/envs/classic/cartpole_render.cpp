// CartPole-v1's picture: gymnasium/envs/classic_control/cartpole.py render(), same geometry
// and colours (600x400 scene, y up, flipped at the end like pygame.transform.flip).
#include "rlrun/envs/classic/classic_render.hpp"
#include "rlrun/frame.hpp"

namespace rlrun {

void draw_cartpole(std::span<const double> state, double /*last_action*/, Frame& frame) {
  constexpr double kWidth = 600, kHeight = 400;
  constexpr double kXThreshold = 2.4, kHalfPoleLength = 0.5;
  constexpr double kScale = kWidth / (kXThreshold * 2);  // world_width = x_threshold * 2
  constexpr double kPoleWidth = 10.0;
  constexpr double kPoleLength = kScale * (2 * kHalfPoleLength);
  constexpr double kCartWidth = 50.0, kCartHeight = 30.0;
  constexpr double kAxleOffset = kCartHeight / 4.0;
  constexpr double kCartY = 100;  // "TOP OF CART" in cartpole.py (the cart's centre line)

  const double x = state[0], theta = state[2];
  frame.begin_scene(kWidth, kHeight, {255, 255, 255});

  const double cart_x = x * kScale + kWidth / 2.0;  // middle of the cart
  {
    const double l = -kCartWidth / 2, r = kCartWidth / 2, t = kCartHeight / 2, b = -kCartHeight / 2;
    const Point cart[] = {{l + cart_x, b + kCartY},
                          {l + cart_x, t + kCartY},
                          {r + cart_x, t + kCartY},
                          {r + cart_x, b + kCartY}};
    frame.polygon(cart, {0, 0, 0});
  }
  {
    const double l = -kPoleWidth / 2, r = kPoleWidth / 2, t = kPoleLength - kPoleWidth / 2,
                 b = -kPoleWidth / 2;
    const Point axle{cart_x, kCartY + kAxleOffset};
    // Positive theta leans the pole to the right: rotate by -theta.
    const Point pole[] = {rotate({l, b}, -theta) + axle, rotate({l, t}, -theta) + axle,
                          rotate({r, t}, -theta) + axle, rotate({r, b}, -theta) + axle};
    frame.polygon(pole, {202, 152, 101});
    // gfxdraw circles take integer centres and radii: int(polewidth / 2) = 5.
    frame.circle({static_cast<double>(static_cast<int>(axle.x)),
                  static_cast<double>(static_cast<int>(axle.y))},
                 static_cast<int>(kPoleWidth / 2), {129, 132, 203});
  }
  // gfxdraw.hline(surf, 0, screen_width, carty): the one-pixel track through pixel row 100.
  frame.line({0, kCartY + 0.5}, {kWidth, kCartY + 0.5}, {0, 0, 0}, 1.0);
  frame.end_scene();
}

void cartpole_state_from_observation(std::span<const float> obs, std::span<double> state) {
  for (size_t i = 0; i < 4; ++i) state[i] = obs[i];  // the observation is the state
}

}  // namespace rlrun
