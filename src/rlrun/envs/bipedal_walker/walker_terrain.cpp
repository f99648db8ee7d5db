#include "rlrun/envs/bipedal_walker/walker_terrain.hpp"

#include <algorithm>
#include <cmath>

#include "rlrun/envs/bipedal_walker/walker_constants.hpp"

namespace rlrun::walker {

namespace {

// numpy's Generator.integers(low, high): uniform in [low, high).
int integers(Rng& rng, int low, int high) {
  return low + static_cast<int>(rng.below(static_cast<uint64_t>(high - low)));
}

double sign(double v) { return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0); }  // np.sign

Quad shifted(const Quad& q, double dx) {
  Quad out = q;
  for (Vec2d& p : out) p.x += dx;
  return out;
}

// _generate_clouds ("Sorry for the clouds, couldn't resist").
void generate_clouds(Rng& rng, Terrain& terrain) {
  constexpr double kS = kTerrainStep;
  for (int i = 0; i < kTerrainLength / 20; ++i) {
    Cloud cloud;
    const double x = rng.uniform(0, kTerrainLength) * kS;
    const double y = kViewportH / kScale * 3 / 4;
    for (int a = 0; a < 5; ++a) {
      // Gymnasium's 3.14, not pi; the x offset is drawn before the y offset.
      const double px = x + 15 * kS * std::sin(3.14 * 2 * a / 5) + rng.uniform(0, 5 * kS);
      const double py = y + 5 * kS * std::cos(3.14 * 2 * a / 5) + rng.uniform(0, 5 * kS);
      cloud.corners[static_cast<size_t>(a)] = {px, py};
    }
    cloud.x1 = cloud.x2 = cloud.corners[0].x;
    for (const Vec2d& p : cloud.corners) {
      cloud.x1 = std::min(cloud.x1, p.x);
      cloud.x2 = std::max(cloud.x2, p.x);
    }
    terrain.clouds.push_back(cloud);
  }
}

}  // namespace

Terrain generate_terrain(Rng& rng, bool hardcore) {
  enum State { kGrass = 0, kStump, kStairs, kPit, kNumStates };  // GRASS, ..., _STATES_
  constexpr double kS = kTerrainStep;
  Terrain terrain;
  terrain.x.reserve(kTerrainLength);
  terrain.y.reserve(kTerrainLength);

  int state = kGrass;
  double velocity = 0.0;
  double y = kTerrainHeight;
  int counter = kTerrainStartpad;
  bool oneshot = false;
  int stair_steps = 0, stair_width = 0, stair_height = 0;
  double original_y = 0;
  for (int i = 0; i < kTerrainLength; ++i) {
    const double x = i * kS;
    terrain.x.push_back(x);
    if (state == kGrass && !oneshot) {
      velocity = 0.8 * velocity + 0.01 * sign(kTerrainHeight - y);
      if (i > kTerrainStartpad) velocity += rng.uniform(-1, 1) / kScale;
      y += velocity;
    } else if (state == kPit && oneshot) {
      counter = integers(rng, 3, 5);
      const Quad wall{{{x, y}, {x + kS, y}, {x + kS, y - 4 * kS}, {x, y - 4 * kS}}};
      terrain.obstacles.push_back({ObstacleKind::kPit, wall});
      terrain.obstacles.push_back({ObstacleKind::kPit, shifted(wall, kS * counter)});
      counter += 2;
      original_y = y;
    } else if (state == kPit && !oneshot) {
      y = original_y;
      if (counter > 1) y -= 4 * kS;
    } else if (state == kStump && oneshot) {
      counter = integers(rng, 1, 3);
      const double side = counter * kS;
      terrain.obstacles.push_back(
          {ObstacleKind::kStump,
           Quad{{{x, y}, {x + side, y}, {x + side, y + side}, {x, y + side}}}});
    } else if (state == kStairs && oneshot) {
      stair_height = rng.uniform() > 0.5 ? +1 : -1;  // np_random.random() > 0.5
      stair_width = integers(rng, 4, 5);
      stair_steps = integers(rng, 3, 5);
      original_y = y;
      for (int s = 0; s < stair_steps; ++s) {
        const double x0 = x + (s * stair_width) * kS, x1 = x + ((1 + s) * stair_width) * kS;
        const double top = y + (s * stair_height) * kS;
        const double bottom = y + (-1 + s * stair_height) * kS;
        terrain.obstacles.push_back(
            {ObstacleKind::kStairs, Quad{{{x0, top}, {x1, top}, {x1, bottom}, {x0, bottom}}}});
      }
      counter = stair_steps * stair_width;
    } else if (state == kStairs && !oneshot) {
      const double s = stair_steps * stair_width - counter - stair_height;
      const double n = s / stair_width;
      y = original_y + (n * stair_height) * kS;
    }
    oneshot = false;
    terrain.y.push_back(y);
    --counter;
    if (counter == 0) {
      counter = integers(rng, kTerrainGrass / 2, kTerrainGrass);
      state = state == kGrass && hardcore ? integers(rng, 1, kNumStates) : kGrass;
      oneshot = true;
    }
  }
  generate_clouds(rng, terrain);
  return terrain;
}

}  // namespace rlrun::walker
