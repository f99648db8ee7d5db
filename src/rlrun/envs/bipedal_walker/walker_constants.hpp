#pragma once
// BipedalWalker-v3's constants, each as Gymnasium 1.0 defines it at the top of
// gymnasium/envs/box2d/bipedal_walker.py (the same names, in kPascalCase). Lengths are in
// Box2D metres: Gymnasium writes them in screen pixels and divides by SCALE.
namespace rlrun::walker {

inline constexpr double kFps = 50;      // FPS: one step is 1/50 s of simulation
inline constexpr double kScale = 30.0;  // SCALE: screen pixels per metre

inline constexpr double kMotorsTorque = 80;  // MOTORS_TORQUE: |action| = 1 gives this torque
inline constexpr double kSpeedHip = 4;       // SPEED_HIP: hip motor speed (rad/s) at any torque
inline constexpr double kSpeedKnee = 6;      // SPEED_KNEE: knee motor speed (rad/s)
inline constexpr double kLidarRange = 160 / kScale;  // LIDAR_RANGE: length of every lidar ray

inline constexpr double kInitialRandom = 5;  // INITIAL_RANDOM: hull push at reset, U(-5, 5) N

// HULL_POLY (pixels): the hull's pentagon, nose to the right.
inline constexpr double kHullPoly[5][2] = {{-30, +9}, {+6, +9}, {+34, +1}, {+34, -8}, {-30, -8}};
inline constexpr double kLegDown = -8 / kScale;  // LEG_DOWN: hips sit this far below the hull
inline constexpr double kLegW = 8 / kScale;      // LEG_W: upper leg width (lower: 0.8 LEG_W)
inline constexpr double kLegH = 34 / kScale;     // LEG_H: length of each leg segment

inline constexpr int kViewportW = 600;  // VIEWPORT_W: rendered width in pixels
inline constexpr int kViewportH = 400;  // VIEWPORT_H: rendered height in pixels

inline constexpr double kTerrainStep = 14 / kScale;  // TERRAIN_STEP: terrain point spacing
inline constexpr int kTerrainLength = 200;           // TERRAIN_LENGTH: terrain points
inline constexpr double kTerrainHeight = kViewportH / kScale / 4;  // TERRAIN_HEIGHT: mean level
inline constexpr int kTerrainGrass = 10;     // TERRAIN_GRASS: grass stretches last [5, 10) steps
inline constexpr int kTerrainStartpad = 20;  // TERRAIN_STARTPAD: flat steps at the start
inline constexpr double kFriction = 2.5;     // FRICTION: of the ground (terrain and obstacles)

// Fixtures (HULL_FD, LEG_FD, LOWER_FD): densities, the hull's friction (the legs keep Box2D's
// default 0.2), and the collision filter: the walker is category 0x20 and collides with
// category 1 (the ground) only, so its own parts never touch each other.
inline constexpr double kHullDensity = 5.0;
inline constexpr double kHullFriction = 0.1;
inline constexpr double kLegDensity = 1.0;
inline constexpr unsigned kGroundCategory = 0x0001;
inline constexpr unsigned kWalkerCategory = 0x0020;

// Joint limits and motor speeds at reset (BipedalWalker.reset's revoluteJointDefs).
inline constexpr double kHipLower = -0.8, kHipUpper = 1.1;
inline constexpr double kKneeLower = -1.6, kKneeUpper = -0.1;
inline constexpr double kLegStartAngle = 0.05;  // legs start at angle i*0.05, i = -1, +1

// Solver settings of BipedalWalker.step: world.Step(1.0 / FPS, 6 * 30, 2 * 30).
inline constexpr int kVelocityIterations = 6 * 30;
inline constexpr int kPositionIterations = 2 * 30;

inline constexpr int kLidarRays = 10;  // self.lidar: 10 rays, ray i at angle 1.5 i / 10
inline constexpr int kObsSize = 24;    // 14 body values + 10 lidar fractions
inline constexpr int kActSize = 4;     // hip 0, knee 0, hip 1, knee 1

// Registered time limits (gymnasium/envs/__init__.py).
inline constexpr int kMaxEpisodeSteps = 1600;
inline constexpr int kMaxEpisodeStepsHardcore = 2000;

}  // namespace rlrun::walker
