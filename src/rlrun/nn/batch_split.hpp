#pragma once
// How a gradient step cuts its work into parts for the run's thread pool (core/thread_pool.hpp,
// `--threads N`): the one rule SplitMlp (a minibatch's columns) and SplitAdam (a parameter
// vector) use. How a range is cut depends only on its size, never on the thread count; each
// part writes only what it owns and sums over parts are taken in part order, so a run is
// bit-identical with 1, 2 or 64 threads. Which thread computes a part is the pool's choice.
#include <Eigen/Core>
#include <type_traits>

#include "rlrun/core/thread_pool.hpp"

namespace rlrun {

// Elements [begin, begin + count) of a range.
struct Part {
  Eigen::Index begin = 0, count = 0;
};

// A pass over a minibatch splits in two only when each half is worth a hand-off to the other
// core: at least kMinSplitColumns columns (the acting batch of a few envs stays whole) and at
// least kMinSplitMultiplyAdds of network work in the whole pass. Measured here: RLtools'
// Pendulum SAC (64x64 networks, batch 100, 0.44 M multiply-adds per pass) ran 5.2 s on two
// threads against 4.4 s on one when every pass split; rl-zoo's DQN CartPole (4-256-256-2,
// batch 64, 4.3 M) halves its update time split.
inline constexpr Eigen::Index kMinSplitColumns = 32;
inline constexpr double kMinSplitMultiplyAdds = 1.5e6;

// Beyond two parts, a minibatch is cut further only while every part keeps at least
// kMinColumnsPerExtraPart columns and kMinMultiplyAddsPerExtraPart of work, so that GEMMs stay
// wide enough to run near peak and each hand-off is worth it on a many-core machine; at most
// kMaxColumnParts. The rl-zoo sizes of the shipped configs (batch <= 256) stay at two parts, as
// they were before the pool; TQC's 512-wide critics at batch 512 go to four.
inline constexpr Eigen::Index kMinColumnsPerExtraPart = 128;
inline constexpr double kMinMultiplyAddsPerExtraPart = 4e6;
inline constexpr int kMaxColumnParts = 16;

// A minibatch of n columns through a network of `multiply_adds_per_column`: 1, 2, 4, 8 or 16
// parts, by size only (never the thread count, so results do not depend on it).
inline int column_parts(Eigen::Index n, Eigen::Index multiply_adds_per_column) {
  const double work = static_cast<double>(n) * static_cast<double>(multiply_adds_per_column);
  if (n < kMinSplitColumns || work < kMinSplitMultiplyAdds) return 1;
  int parts = 2;
  while (parts * 2 <= kMaxColumnParts && n / (parts * 2) >= kMinColumnsPerExtraPart &&
         work / (parts * 2) >= kMinMultiplyAddsPerExtraPart)
    parts *= 2;
  return parts;
}
// Part `part` of n columns cut into `parts` consecutive ranges, n * part / parts onwards (two
// parts: [0, n/2) and [n/2, n)).
inline Part column_part(Eigen::Index n, int parts, int part) {
  const Eigen::Index begin = n * part / parts, end = n * (part + 1) / parts;
  return {begin, end - begin};
}

// A parameter vector of n floats (gradient sums, optimizer steps): two parts, the first a whole
// number of 64-byte cache lines (16 floats), so the two cores never write the same line.
inline Part param_part(Eigen::Index n, int part) {
  const Eigen::Index split = n / 2 / 16 * 16;
  return part == 0 ? Part{0, split} : Part{split, n - split};
}

// fn(0), ..., fn(parts - 1) on the threads of `pool` (null: all on the calling thread, in part
// order); returns when all are done. fn(k) must write only what part k owns.
template <class F>
void run_parts(ThreadPool* pool, int parts, F&& fn) {
  if (pool == nullptr || parts == 1) {
    for (int k = 0; k < parts; ++k) fn(k);
    return;
  }
  pool->run(parts, fn);
}

}  // namespace rlrun
