#pragma once
// Two computations of the tasks' Python code whose rounding is NumPy's (NumPy 1.x, Debian 12's
// 1.24.2 with Debian's reference BLAS), reproduced to the last bit:
//
//   euclidean_norm(v)  np.linalg.norm(v) of a 1-D float64 array (also with ord=2): NumPy
//                      computes sqrt(dot(v, v)) and hands the dot product to BLAS ddot, which
//                      adds the products from the first to the last (the reference BLAS
//                      unrolls by 5 but still adds left to right); never hypot.
//   scalar_squared(x)  x ** 2 of a NumPy float64 scalar (InvertedDoublePendulum's
//                      `0.01 * x**2`): NumPy's scalar power calls the C library's pow(x, 2.0),
//                      which on glibc rounds differently from x * x for about 1 value in 1000
//                      (measured: 186 of 200 000 random values). Compilers turn pow(x, 2.0)
//                      into x * x, so the call is made so that they cannot.
#include <span>

namespace rlrun::mujoco {

double euclidean_norm(std::span<const double> v);
double scalar_squared(double x);

}  // namespace rlrun::mujoco
