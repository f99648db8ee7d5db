#!/usr/bin/env python3
"""The rational tanh of rlrun's network kernels (src/rlrun/nn/dense_kernel_set.hpp).

tanh(x) ~= x P(x^2) / Q(x^2) on [-C, C], C = 9 (beyond it tanh rounds to +-1 in float), with P
and Q of degree 4 in x^2, Q(0) = 1 (P(0) comes out 1 to float precision). Fitted here by Lawson's iteratively reweighted
least squares on the linearised problem P(z) - f(z) Q(z) = 0, f(z) = tanh(x) / x, which converges
towards the minimax of the relative error. Then every coefficient is rounded to float and the
formula is evaluated as the kernels do (float32, fused multiply-adds in Horner order, one
division) on a dense grid, and its worst error reported in float ulps.

    /usr/bin/python3 scripts/data/fit_tanh.py      # needs numpy; prints the coefficients and errors
"""
import numpy as np

C = 9.0
DEGREE_P, DEGREE_Q = 4, 4


def fit(iterations=60):
    x = np.sort(np.concatenate([np.linspace(0.0, C, 20001)[1:], np.geomspace(1e-4, 0.5, 2000)]))
    z = x * x
    f = np.tanh(x) / x
    weights = np.ones_like(x)
    q_prev = np.ones_like(x)
    for _ in range(iterations):
        a = np.hstack([np.vstack([z**i for i in range(DEGREE_P + 1)]).T,
                       -np.vstack([f * z**i for i in range(1, DEGREE_Q + 1)]).T])
        scale = np.sqrt(weights) / np.abs(q_prev) / f  # relative error of P/Q
        coef, *_ = np.linalg.lstsq(a * scale[:, None], f * scale, rcond=None)
        p = coef[:DEGREE_P + 1]
        q = np.concatenate([[1.0], coef[DEGREE_P + 1:]])
        pz, qz = np.polyval(p[::-1], z), np.polyval(q[::-1], z)
        err = np.abs(pz / qz - f) / f
        q_prev = qz
        weights = weights * np.sqrt(err / err.max()) + 1e-12
        weights /= weights.sum()
    return p, q, err.max()


def to_float(v):
    return np.asarray(v, dtype=np.float64).astype(np.float32)


def fma(a, b, c):  # one rounding: a * b is exact in double for float inputs
    return to_float(a.astype(np.float64) * b + c)


def float_tanh(x, p, q):
    x = np.minimum(to_float(C), np.maximum(to_float(-C), x))
    z = to_float(x.astype(np.float64) * x)
    pz = np.full_like(z, p[-1])
    for c in p[-2::-1]:
        pz = fma(pz, z, np.full_like(z, c))
    qz = np.full_like(z, q[-1])
    for c in q[-2::-1]:
        qz = fma(qz, z, np.full_like(z, c))
    return to_float(to_float(x.astype(np.float64) * pz).astype(np.float64) / qz)


def main():
    p, q, err = fit()
    p32, q32 = to_float(p), to_float(q)
    x = to_float(np.concatenate([np.linspace(-12.0, 12.0, 2000001), np.geomspace(1e-30, 1.0, 100000)]))
    y = float_tanh(x, p32, q32)
    exact = np.tanh(x.astype(np.float64))
    ulps = np.abs(y - exact) / np.spacing(np.abs(exact).astype(np.float32)).astype(np.float64)
    print("P (z^0..z^4):", ", ".join("%.9e" % v for v in p32))
    print("Q (z^0..z^4):", ", ".join("%.9e" % v for v in q32))
    print("max relative error of P/Q in double: %.3g" % err)
    print("max error in float: %.2f ulp (at x = %.6g)" % (ulps.max(), x[ulps.argmax()]))


if __name__ == "__main__":
    main()
