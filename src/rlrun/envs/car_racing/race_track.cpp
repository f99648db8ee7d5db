#include "rlrun/envs/car_racing/race_track.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rlrun::car_racing {

namespace {

constexpr double kPi = std::numbers::pi;
// _create_track gives up on a curve after this many steps (no_freeze).
constexpr int kMaxTrackSteps = 2500;
// A track read from outside: more points than Gymnasium's generator can make is refused.
constexpr size_t kMaxTrackPoints = 10000;

// Python's seq[i] for -len <= i < len.
template <class T>
const T& wrapped(std::span<const T> seq, long i) {
  const long n = static_cast<long>(seq.size());
  return seq[static_cast<size_t>(i < 0 ? i + n : i)];
}

struct Checkpoint {
  double alpha, x, y;
};

// Twelve checkpoints around the circle, each at a random angle within its sector and a random
// radius; the first sits at angle 0 and the last at 11/12 of the circle, both at 1.5 TRACK_RAD,
// so the track starts and ends on the same wide arc. Both draws happen for every checkpoint.
std::array<Checkpoint, kCheckpoints> draw_checkpoints(Rng& rng) {
  std::array<Checkpoint, kCheckpoints> out{};
  for (int c = 0; c < kCheckpoints; ++c) {
    const double noise = rng.uniform(0.0, 2 * kPi * 1 / kCheckpoints);
    double alpha = 2 * kPi * c / kCheckpoints + noise;
    double rad = rng.uniform(kTrackRad / 3, kTrackRad);
    if (c == 0) {
      alpha = 0;
      rad = 1.5 * kTrackRad;
    }
    if (c == kCheckpoints - 1) {
      alpha = 2 * kPi * c / kCheckpoints;
      rad = 1.5 * kTrackRad;
    }
    out[c] = {alpha, rad * std::cos(alpha), rad * std::sin(alpha)};
  }
  return out;
}

// The first checkpoint (counting from dest_i, cyclically) whose angle is not below alpha;
// after a whole turn without one, alpha is taken a turn lower (Gymnasium's nested loops).
const Checkpoint& find_destination(const std::array<Checkpoint, kCheckpoints>& checkpoints,
                                   double& alpha, int& dest_i) {
  while (true) {
    while (true) {
      const Checkpoint& dest = checkpoints[dest_i % kCheckpoints];
      if (alpha <= dest.alpha) return dest;
      ++dest_i;
      if (dest_i % kCheckpoints == 0) break;
    }
    alpha -= 2 * kPi;
  }
}

// Steers a point along the checkpoints for up to five laps: each step turns the heading beta
// towards the destination (at most TRACK_TURN_RATE) and moves TRACK_DETAIL_STEP.
std::vector<TrackPoint> trace_curve(const std::array<Checkpoint, kCheckpoints>& checkpoints) {
  double x = 1.5 * kTrackRad, y = 0, beta = 0;
  int dest_i = 0, laps = 0;
  bool visited_other_side = false;
  std::vector<TrackPoint> track;
  for (int step = 0; step < kMaxTrackSteps; ++step) {
    double alpha = std::atan2(y, x);
    if (visited_other_side && alpha > 0) {
      ++laps;
      visited_other_side = false;
    }
    if (alpha < 0) {
      visited_other_side = true;
      alpha += 2 * kPi;
    }
    const Checkpoint& dest = find_destination(checkpoints, alpha, dest_i);
    const double r1x = std::cos(beta), r1y = std::sin(beta);
    const double p1x = -r1y, p1y = r1x;
    // The destination vector projected on the radius (the heading's normal).
    double proj = r1x * (dest.x - x) + r1y * (dest.y - y);
    while (beta - alpha > 1.5 * kPi) beta -= 2 * kPi;
    while (beta - alpha < -1.5 * kPi) beta += 2 * kPi;
    const double prev_beta = beta;
    proj *= kScale;
    if (proj > 0.3) beta -= std::min(kTrackTurnRate, std::abs(0.001 * proj));
    if (proj < -0.3) beta += std::min(kTrackTurnRate, std::abs(0.001 * proj));
    x += p1x * kTrackDetailStep;
    y += p1y * kTrackDetailStep;
    track.push_back({alpha, prev_beta * 0.5 + beta * 0.5, x, y});
    if (laps > 4) break;
  }
  return track;
}

double quad_area(const Quad& q) {
  double twice = 0;
  for (int k = 0; k < 4; ++k) {
    const Vec2& a = q[k];
    const Vec2& b = q[(k + 1) % 4];
    twice += a[0] * b[1] - b[0] * a[1];
  }
  return 0.5 * std::abs(twice);
}

Vec2 offset(double x, double y, double beta, double distance) {
  return {x + distance * std::cos(beta), y + distance * std::sin(beta)};
}

// border[i]: the BORDER_MIN_COUNT turns ending at point i all go the same way and are sharp;
// then every marked point marks the three before it. Both loops run in place with Python's
// negative indices, as Gymnasium's do (marks made through the wrap-around spread once more).
std::vector<bool> hard_turns(std::span<const TrackPoint> track) {
  const long n = static_cast<long>(track.size());
  std::vector<bool> border(track.size(), false);
  for (long i = 0; i < n; ++i) {
    bool good = true;
    double oneside = 0;
    for (long neg = 0; neg < kBorderMinCount; ++neg) {
      const double beta1 = wrapped(track, i - neg).beta;
      const double beta2 = wrapped(track, i - neg - 1).beta;
      good = good && std::abs(beta1 - beta2) > kTrackTurnRate * 0.2;
      oneside += sign(beta1 - beta2);
    }
    border[i] = good && std::abs(oneside) == kBorderMinCount;
  }
  for (long i = 0; i < n; ++i)
    for (long neg = 0; neg < kBorderMinCount; ++neg) {
      const long j = i - neg < 0 ? i - neg + n : i - neg;
      if (border[i]) border[j] = true;
    }
  return border;
}

}  // namespace

std::optional<std::vector<TrackPoint>> generate_track(Rng& rng) {
  const auto checkpoints = draw_checkpoints(rng);
  const double start_alpha = 2 * kPi * (-0.5) / kCheckpoints;
  const std::vector<TrackPoint> curve = trace_curve(checkpoints);

  // The closed loop: between the last two passes through the start angle, counted from the
  // end (the first lap is ignored, the second is OK).
  long i1 = -1, i2 = -1;
  for (long i = static_cast<long>(curve.size()) - 1; i > 0; --i) {
    const bool pass_through_start =
        curve[i].alpha > start_alpha && curve[i - 1].alpha <= start_alpha;
    if (pass_through_start && i2 == -1) {
      i2 = i;
    } else if (pass_through_start && i1 == -1) {
      i1 = i;
      break;
    }
  }
  if (i1 == -1 || i2 - 1 - i1 < 3) return std::nullopt;
  std::vector<TrackPoint> track(curve.begin() + i1, curve.begin() + (i2 - 1));

  // The head and tail must meet: their gap across the first heading at most one step.
  const double perp_x = std::cos(track.front().beta), perp_y = std::sin(track.front().beta);
  const double dx = perp_x * (track.front().x - track.back().x);
  const double dy = perp_y * (track.front().y - track.back().y);
  if (std::sqrt(dx * dx + dy * dy) > kTrackDetailStep) return std::nullopt;
  return track;
}

Road build_road(std::span<const TrackPoint> track) {
  const std::vector<bool> border = hard_turns(track);
  Road road;
  road.tiles.reserve(track.size());
  for (long i = 0; i < static_cast<long>(track.size()); ++i) {
    const TrackPoint& p1 = track[i];
    const TrackPoint& p2 = wrapped(track, i - 1);
    const Vec2 road1_l = offset(p1.x, p1.y, p1.beta, -kTrackWidth);
    const Vec2 road1_r = offset(p1.x, p1.y, p1.beta, +kTrackWidth);
    const Vec2 road2_l = offset(p2.x, p2.y, p2.beta, -kTrackWidth);
    const Vec2 road2_r = offset(p2.x, p2.y, p2.beta, +kTrackWidth);
    road.tiles.push_back({road1_l, road1_r, road2_r, road2_l});
    if (border[i]) {
      const double side = sign(p2.beta - p1.beta);  // the outside of the turn
      const Vec2 b1_l = offset(p1.x, p1.y, p1.beta, side * kTrackWidth);
      const Vec2 b1_r = offset(p1.x, p1.y, p1.beta, side * (kTrackWidth + kBorder));
      const Vec2 b2_l = offset(p2.x, p2.y, p2.beta, side * kTrackWidth);
      const Vec2 b2_r = offset(p2.x, p2.y, p2.beta, side * (kTrackWidth + kBorder));
      road.kerbs.push_back({static_cast<int>(i), {b1_l, b1_r, b2_r, b2_l}, i % 2 != 0});
    }
  }
  return road;
}

void check_track(std::span<const TrackPoint> track) {
  if (track.size() < 3 || track.size() > kMaxTrackPoints)
    throw std::invalid_argument("a track needs 3 to " + std::to_string(kMaxTrackPoints) +
                                " points (alpha, beta, x, y), got " + std::to_string(track.size()));
  for (size_t i = 0; i < track.size(); ++i) {
    const TrackPoint& p = track[i];
    const std::string where = "track point " + std::to_string(i);
    if (!std::isfinite(p.alpha) || !std::isfinite(p.beta) || !std::isfinite(p.x) ||
        !std::isfinite(p.y))
      throw std::invalid_argument(where + " is not finite");
    if (std::abs(p.x) > kPlayfield || std::abs(p.y) > kPlayfield)
      throw std::invalid_argument(
          where + " lies outside the playfield (|x|, |y| <= " + std::to_string(kPlayfield) + ")");
    if (std::abs(p.beta) > 1e3)
      throw std::invalid_argument(where + ": beta must be an angle in radians");
  }
  const Road road = build_road(track);
  for (size_t i = 0; i < road.tiles.size(); ++i)
    if (quad_area(road.tiles[i]) < 1e-3)
      throw std::invalid_argument("track point " + std::to_string(i) +
                                  " makes a degenerate road tile (it repeats the point "
                                  "before it or folds the road)");
}

}  // namespace rlrun::car_racing
