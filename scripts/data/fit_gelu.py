#!/usr/bin/env python3
"""The normal CDF behind rlrun's GELU kernels (src/rlrun/nn/dense_kernel_set.hpp).

torch.nn.GELU (approximate='none') is gelu(x) = x Phi(x), Phi(x) = (1 + erf(x / sqrt(2))) / 2 the
standard normal CDF, and gelu'(x) = Phi(x) + x phi(x), phi(x) = exp(-x^2 / 2) / sqrt(2 pi). The
kernels compute, for a = |x|,

    Phi(-a) = exp(-a^2 / 2) S(a) / 2,   S(a) = erfcx(a / sqrt(2)) ~= P(a) / Q(a),

and Phi(x) = 1 - Phi(-a) for x > 0: a scaled-erfc form (as in W. J. Cody, "Rational Chebyshev
approximations for the error function", Math. Comp. 23 (1969), which writes erfc(x) =
exp(-x^2) R(x) with a rational R), here with a single rational over the whole range, so there is
no erf / erfc split and no branch. Phi(-a) keeps its relative accuracy in the far tail (1 + erf
would cancel), and exp(-a^2 / 2) is also phi's, so the derivative costs no second exp.

S is smooth and decreasing from S(0) = 1 to ~sqrt(2 / pi) / a; P of degree 4 and Q of degree 5
(Q(0) = 1, P(0) comes out 1) fit it on [0, A], A = 13.2 (|gelu(x)| = |x| Phi(x) falls below
float's smallest normal at x = -13.15; beyond A the kernels take Phi(-a) = 0, and exp(-A^2 / 2)
is still above the kernels' exp clamp at -87.3), with all coefficients positive, so
P and Q are well-conditioned sums on a >= 0. Fitted here by Lawson's iteratively reweighted
least squares on the linearised problem P(a) - S(a) Q(a) = 0, which converges towards the
minimax of the relative error (as scripts/data/fit_tanh.py). Then every coefficient is rounded
to float and gelu and gelu' are evaluated as the kernels do (float32, fused multiply-adds in
Horner order, the kernels' Cephes-style exp, a^2 split exactly into its rounded value and
error) on a dense grid, and their worst errors reported in float ulps.

    /usr/bin/python3 scripts/data/fit_gelu.py   # needs numpy and scipy; prints coefficients, errors
"""
import numpy as np
from scipy.special import erfcx, ndtr

A = 13.2
DEGREE_P, DEGREE_Q = 4, 5


def fit(iterations=80):
    a = np.linspace(0.0, A, 40001)
    f = erfcx(a / np.sqrt(2.0))
    weights = np.ones_like(a)
    q_prev = np.ones_like(a)
    for _ in range(iterations):
        m = np.hstack([np.vstack([a**i for i in range(DEGREE_P + 1)]).T,
                       -np.vstack([f * a**i for i in range(1, DEGREE_Q + 1)]).T])
        scale = np.sqrt(weights) / np.abs(q_prev) / f  # relative error of P/Q
        coef, *_ = np.linalg.lstsq(m * scale[:, None], f * scale, rcond=None)
        p = coef[:DEGREE_P + 1]
        q = np.concatenate([[1.0], coef[DEGREE_P + 1:]])
        pa, qa = np.polyval(p[::-1], a), np.polyval(q[::-1], a)
        err = np.abs(pa / qa - f) / f
        q_prev = qa
        weights = weights * np.sqrt(err / err.max()) + 1e-12
        weights /= weights.sum()
    return p, q, err.max()


def f32(v):
    return np.asarray(v, dtype=np.float64).astype(np.float32)


def fma(a, b, c):  # one rounding: a * b is exact in double for float inputs
    return f32(np.float64(1.0) * a * b + c)


def kernel_exp(x):
    """The kernels' exp (dense_kernel_set.hpp), in float32."""
    x = np.minimum(f32(88.3), np.maximum(f32(-87.3), x))
    n = np.floor(fma(x, f32(1.44269504088896341), f32(0.5)))
    r = fma(n, f32(-0.693359375), x)
    r = fma(n, f32(2.12194440e-4), r)
    p = np.full_like(r, f32(1.9875691500e-4))
    for c in (1.3981999507e-3, 8.3334519073e-3, 4.1665795894e-2, 1.6666665459e-1,
              5.0000001201e-1):
        p = fma(p, r, f32(c))
    p = fma(p, f32(r * r), f32(r + f32(1.0)))
    return f32(p * np.ldexp(np.float32(1.0), n.astype(np.int32)))


def kernel_gelu(x, p, q):
    """gelu(x) and gelu'(x) as the kernels compute them, in float32."""
    a = np.minimum(f32(A), np.abs(x))
    u = f32(a * a)
    u_err = f32(np.float64(a) * a - u)  # exact: what fma(a, a, -u) gives
    e = kernel_exp(f32(u * f32(-0.5)))
    e = fma(e, f32(u_err * f32(-0.5)), e)  # exp(-(u + u_err) / 2) = exp(-u / 2) (1 - u_err / 2)
    e = np.where(np.abs(x) > A, f32(0.0), e)
    pa = np.full_like(a, p[-1])
    for c in p[-2::-1]:
        pa = fma(pa, a, np.full_like(a, c))
    qa = np.full_like(a, q[-1])
    for c in q[-2::-1]:
        qa = fma(qa, a, np.full_like(a, c))
    tail = f32(f32(e * f32(0.5)) * f32(pa / qa))  # Phi(-|x|)
    cdf = np.where(x > 0, f32(f32(1.0) - tail), tail)
    gelu = f32(x * cdf)
    grad = fma(x, f32(e * f32(0.3989422804014327)), cdf)
    return gelu, grad


def ulps(got, want):
    return np.abs(got - want) / np.spacing(np.abs(want).astype(np.float32)).astype(np.float64)


def main():
    p, q, err = fit()
    p32, q32 = f32(p), f32(q)
    x = f32(np.concatenate([np.linspace(-14.0, 14.0, 4000001),
                            np.geomspace(1e-30, 1.0, 100000), -np.geomspace(1e-30, 1.0, 100000)]))
    gelu, grad = kernel_gelu(x, p32, q32)
    xd = x.astype(np.float64)
    cdf = ndtr(xd)
    want_gelu = xd * cdf
    want_grad = cdf + xd * np.exp(-0.5 * xd * xd) / np.sqrt(2.0 * np.pi)
    # Relative accuracy (ulps) where the value is at least 1e-30; below (x < -11.6, towards float's
    # smallest normal 1.2e-38 and the cut at |x| = A) the absolute error.
    normal = np.abs(want_gelu) >= 1e-30
    u = ulps(gelu, want_gelu)[normal]
    # gelu' crosses 0 near x = -0.75: its error in ulps of the larger term, Phi(x) or |x phi(x)|.
    scale = np.maximum(cdf, np.abs(want_grad - cdf))
    grad_normal = scale >= 1e-30
    g = (np.abs(grad - want_grad) / np.spacing(scale.astype(np.float32)).astype(np.float64))
    print("P (a^0..a^%d):" % DEGREE_P, ", ".join("%.9e" % v for v in p32))
    print("Q (a^0..a^%d):" % DEGREE_Q, ", ".join("%.9e" % v for v in q32))
    print("max relative error of P/Q in double: %.3g" % err)
    print("gelu in float: max %.2f ulp (at x = %.6g), max relative error %.3g; "
          "absolute error below 1e-30: %.3g"
          % (u.max(), x[normal][u.argmax()],
             (np.abs(gelu - want_gelu)[normal] / np.abs(want_gelu[normal])).max(),
             np.abs(gelu - want_gelu)[~normal].max()))
    print("gelu' in float: max %.2f ulp of max(Phi, |x phi|) (at x = %.6g); absolute error "
          "below 1e-30: %.3g" % (g[grad_normal].max(), x[grad_normal][g[grad_normal].argmax()],
                                 np.abs(grad - want_grad)[~grad_normal].max()))

if __name__ == "__main__":
    main()
