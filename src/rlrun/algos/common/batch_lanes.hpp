#pragma once
// Data parallelism for an off-policy gradient step: a minibatch of n columns is split into two
// lanes, each a replica of the networks that runs its half of the forward and backward passes;
// the replica's parameter gradients are then added to the primary lane's, which is the
// gradient torch computes over the whole batch (up to float summation order). Lane 1 runs on
// ForkJoin's worker when it is on (RLRUN_THREADS=2), after lane 0 on the calling thread
// otherwise. The split depends on n only, so a run is bit-identical with one or two threads.
// Splitting the batch rather than the networks keeps both cores busy through every phase
// (actor updates too) and works for any number of critics.
#include <Eigen/Core>
#include <type_traits>

#include "rlrun/core/fork_join.hpp"

namespace rlrun {

// Below this many samples one lane does everything: handing half of a small batch to the other
// core costs more than it saves.
inline constexpr Eigen::Index kMinSplitBatch = 32;

// Runs fn(lane, begin, count) for each lane's columns [begin, begin + count) of a batch of n:
// lane 0 alone when n < kMinSplitBatch, else lanes 0 and 1 on the two halves. Returns the
// number of lanes used. fn must write only lane-owned state and its own columns.
template <class F>
int run_batch_lanes(Eigen::Index n, F&& fn) {
  if (n < kMinSplitBatch) {
    fn(0, Eigen::Index{0}, n);
    return 1;
  }
  // Each half is captured through one reference, so std::function stores it in place (no
  // allocation per gradient step).
  struct Slice {
    std::remove_reference_t<F>* fn;
    int lane;
    Eigen::Index begin, count;
    void operator()() const { (*fn)(lane, begin, count); }
  };
  const Eigen::Index half = n / 2;
  const Slice first{&fn, 0, 0, half}, second{&fn, 1, half, n - half};
  ForkJoin::shared().run([&first] { first(); }, [&second] { second(); });
  return 2;
}

}  // namespace rlrun
