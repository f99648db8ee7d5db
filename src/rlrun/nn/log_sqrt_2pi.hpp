#pragma once
// log(sqrt(2 pi)): the constant of a normal density's log, as torch's Normal.log_prob writes it
// (torch/distributions/normal.py: -log(scale) - log(sqrt(2 pi)) - ...), in float.

namespace rlrun {

inline constexpr float kLogSqrt2Pi = 0.91893853320467274f;

}  // namespace rlrun
