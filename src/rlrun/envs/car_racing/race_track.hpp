#pragma once
// CarRacing's track: CarRacing._create_track in gymnasium/envs/box2d/car_racing.py (Gymnasium
// 1.0.0, by Oleg Klimov), split into the random closed curve (generate_track) and the road it
// becomes (build_road: tiles, red-white kerbs on hard turns). Pure geometry, no Box2D: the env
// (car_racing.cpp) turns the tiles into sensor bodies.
#include <array>
#include <optional>
#include <span>
#include <vector>

#include "rlrun/env/race_track_state.hpp"
#include "rlrun/rng.hpp"

namespace rlrun::car_racing {

// Module constants of car_racing.py, same names.
inline constexpr double kScale = 6.0;                    // SCALE: track scale
inline constexpr double kTrackRad = 900 / kScale;        // TRACK_RAD
inline constexpr double kPlayfield = 2000 / kScale;      // PLAYFIELD: game-over boundary
inline constexpr double kTrackDetailStep = 21 / kScale;  // TRACK_DETAIL_STEP
inline constexpr double kTrackTurnRate = 0.31;           // TRACK_TURN_RATE
inline constexpr double kTrackWidth = 40 / kScale;       // TRACK_WIDTH (half the road)
inline constexpr double kBorder = 8 / kScale;            // BORDER: kerb width
inline constexpr int kBorderMinCount = 4;                // BORDER_MIN_COUNT
inline constexpr double kGrassDim = kPlayfield / 20.0;   // GRASS_DIM: grass patch size
inline constexpr int kCheckpoints = 12;                  // CHECKPOINTS in _create_track

using Vec2 = std::array<double, 2>;

// numpy.sign, which Gymnasium's track, car and drawing code use: -1, 0 or +1.
inline double sign(double v) { return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0); }
using Quad = std::array<Vec2, 4>;

// One random closed track from `rng`, or nothing when this attempt fails (the loop does not
// close well enough: _create_track returns False and reset() draws again). The draws are
// _create_track's, in its order: per checkpoint a noise angle, then a radius.
std::optional<std::vector<TrackPoint>> generate_track(Rng& rng);

// The road of a track: one quad per track point i, from point i-1 to point i ("road1" is
// point i, "road2" point i-1, wrapping around for i = 0 as Python's track[-1] does), and a kerb
// quad on the outside of every hard turn (BORDER_MIN_COUNT consecutive turns the same way,
// each sharper than TRACK_TURN_RATE * 0.2), white on even tiles and red on odd ones.
struct RoadKerb {
  int tile = 0;  // drawn right after this tile, as Gymnasium appends it to road_poly
  Quad quad{};
  bool red = false;
};
struct Road {
  std::vector<Quad> tiles;
  std::vector<RoadKerb> kerbs;
};
Road build_road(std::span<const TrackPoint> track);

// Throws std::invalid_argument unless the track can be a road: at least 3 points, finite
// values, consecutive points no further apart than the playfield and every tile a proper
// quad (a track read from Python or a file is checked before Box2D sees it).
void check_track(std::span<const TrackPoint> track);

}  // namespace rlrun::car_racing
