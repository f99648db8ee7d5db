#pragma once
// How a gradient step shares its work between the two cores (core/fork_join.hpp, `--threads
// 1|2`): the one rule SplitMlp (a minibatch's columns) and SplitAdam (a parameter vector) use.
// A part is computed on the calling thread (part 0) or on ForkJoin's worker (part 1; after part
// 0 on the calling thread when the worker is off). How a range is split depends only on its
// size, never on the thread count, and sums over parts are taken in part order, so a run is
// bit-identical with one thread or two.
#include <Eigen/Core>
#include <type_traits>

#include "rlrun/core/fork_join.hpp"

namespace rlrun {

// Elements [begin, begin + count) of a range.
struct Part {
  Eigen::Index begin = 0, count = 0;
};

// Below this many minibatch columns one part does everything: handing half of a small batch
// to the other core costs more than it saves (the acting batch of a few envs stays whole).
inline constexpr Eigen::Index kMinSplitColumns = 32;

// A minibatch of n columns: one part below kMinSplitColumns, else the halves [0, n/2) and
// [n/2, n).
inline int column_parts(Eigen::Index n) { return n < kMinSplitColumns ? 1 : 2; }
inline Part column_part(Eigen::Index n, int part) {
  if (column_parts(n) == 1) return {0, n};
  const Eigen::Index half = n / 2;
  return part == 0 ? Part{0, half} : Part{half, n - half};
}

// A parameter vector of n floats (gradient sums, optimizer steps): two parts, the first a whole
// number of 64-byte cache lines (16 floats), so the two cores never write the same line.
inline Part param_part(Eigen::Index n, int part) {
  const Eigen::Index split = n / 2 / 16 * 16;
  return part == 0 ? Part{0, split} : Part{split, n - split};
}

// Runs fn(0) here and, when parts is 2, fn(1) on the worker of `fork_join` (null: the process's
// ForkJoin::shared(), made on this first use); returns when both are done. fn(k) must write
// only what part k owns.
template <class F>
void run_parts(ForkJoin* fork_join, int parts, F&& fn) {
  if (parts == 1) {
    fn(0);
    return;
  }
  // Each part is captured through one reference, so std::function stores it in place (no
  // allocation per gradient step).
  struct Call {
    std::remove_reference_t<F>* fn;
    int part;
    void operator()() const { (*fn)(part); }
  };
  const Call first{&fn, 0}, second{&fn, 1};
  (fork_join ? *fork_join : ForkJoin::shared()).run([&first] { first(); }, [&second] { second(); });
}

}  // namespace rlrun
