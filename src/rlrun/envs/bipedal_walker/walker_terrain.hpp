#pragma once
// BipedalWalker's terrain, drawn from the env's RNG at reset exactly as Gymnasium 1.0's
// BipedalWalker._generate_terrain and _generate_clouds (gymnasium/envs/box2d/bipedal_walker.py)
// draw it: TERRAIN_LENGTH points TERRAIN_STEP apart whose heights follow a damped random walk
// ("grass"), flat over the start pad; in hardcore mode each grass stretch is followed by an
// obstacle chosen uniformly among a stump, stairs (up or down) and a pit. The obstacles are
// static polygons; the ground line is made of edges between consecutive points. Plain data:
// the env turns it into Box2D bodies and the renderer draws it.
#include <array>
#include <vector>

#include "rlrun/rng.hpp"

namespace rlrun::walker {

struct Vec2d {
  double x = 0, y = 0;
};

// A four-cornered static obstacle (stump, stair step, pit wall) in world coordinates.
using Quad = std::array<Vec2d, 4>;

// What _generate_terrain's state machine was in when it built an obstacle.
enum class ObstacleKind { kStump, kStairs, kPit };

struct Obstacle {
  ObstacleKind kind;
  Quad corners;
};

// A cloud: five corners and its x extent (drawn with parallax by the renderer only).
struct Cloud {
  std::array<Vec2d, 5> corners;
  double x1 = 0, x2 = 0;
};

struct Terrain {
  std::vector<double> x, y;         // TERRAIN_LENGTH ground points (terrain_x, terrain_y)
  std::vector<Obstacle> obstacles;  // in creation order
  std::vector<Cloud> clouds;        // TERRAIN_LENGTH / 20 of them
};

// Draws the terrain and then the clouds from `rng` (in that order, as BipedalWalker.reset
// does, so the hull's initial push is the next draw).
Terrain generate_terrain(Rng& rng, bool hardcore);

}  // namespace rlrun::walker
