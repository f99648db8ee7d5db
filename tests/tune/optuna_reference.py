"""Prints the reference numbers pasted into tests/tune/test_parzen_estimator.cpp and
test_truncnorm.cpp: Optuna 3.1's own _ParzenEstimator and _truncnorm on small inputs.

Run with Debian's python3-optuna 3.1.0:  /usr/bin/python3 tests/tune/optuna_reference.py
"""
import numpy as np
import optuna
from optuna.distributions import CategoricalDistribution, FloatDistribution, IntDistribution
from optuna.samplers._tpe import _truncnorm as truncnorm
from optuna.samplers._tpe.parzen_estimator import _ParzenEstimator, _ParzenEstimatorParameters
from optuna.samplers._tpe.sampler import default_weights

assert optuna.__version__ == "3.1.0", optuna.__version__


def show(name, values):
    print(f"  {name}: {{{', '.join(repr(float(v)) for v in np.atleast_1d(values))}}}")


def params(multivariate):
    return _ParzenEstimatorParameters(True, 1.0, True, False, default_weights, multivariate)


print("truncnorm")
for a, b in [(-1.0, 2.0), (-40.0, -30.0), (30.0, 40.0), (-3.0, -2.5), (5.0, 9.0), (-0.5, 0.5)]:
    print(f"  log_gauss_mass({a}, {b}) = {truncnorm._log_gauss_mass(np.array([a]), np.array([b]))[0]!r}")
for a in [-30.0, -5.0, 0.3, 7.0]:
    print(f"  log_ndtr({a}) = {truncnorm._log_ndtr_single(a)!r}")
for q, a, b in [(0.3, -1.0, 2.0), (0.9, 3.0, 8.0), (0.1, -9.0, -4.0), (0.5, -35.0, -33.0)]:
    print(f"  ppf({q}, {a}, {b}) = {truncnorm.ppf(np.array([q]), a, b)[0]!r}")
print(f"  logpdf(0.7, -1, 2, 0.5, 0.25) = {truncnorm.logpdf(np.array([0.7]), -1.0, 2.0, 0.5, 0.25)[0]!r}")

# Multivariate: four parameters of every kind, four observations.
space = {
    "c": CategoricalDistribution(["a", "b", "c"]),
    "lr": FloatDistribution(1e-4, 1e-1, log=True),
    "n": IntDistribution(0, 10, step=2),
    "x": FloatDistribution(-5.0, 5.0),
}
obs = {
    "c": np.array([0.0, 2.0, 2.0, 1.0]),
    "lr": np.array([1e-3, 3e-2, 2e-4, 5e-3]),
    "n": np.array([2.0, 10.0, 4.0, 4.0]),
    "x": np.array([-4.0, 0.5, 1.0, 3.0]),
}
pe = _ParzenEstimator(obs, space, params(True))
print("multivariate")
show("weights", pe._weights)
for name in ["lr", "n", "x"]:
    show(f"{name} mus", pe._mus[name])
    show(f"{name} sigmas", pe._sigmas[name])
    print(f"  {name} low/high/q: {pe._low[name]!r} {pe._high[name]!r} {pe._q[name]!r}")
show("c weights (row-major)", pe._categorical_weights["c"].ravel())
samples = {
    "c": np.array([0, 2, 1]),
    "lr": np.array([1e-3, 0.08, 1e-4]),
    "n": np.array([4.0, 0.0, 10.0]),
    "x": np.array([0.0, -4.9, 4.5]),
}
show("log_pdf", pe.log_pdf(samples))

# Univariate (neighbour-distance sigmas): one float, one int (step 1), one log int.
print("univariate")
uspace = {
    "u": FloatDistribution(0.0, 10.0),
    "k": IntDistribution(1, 8),
    "m": IntDistribution(1, 1024, log=True),
}
uobs = {
    "u": np.array([1.0, 2.0, 2.0, 7.0, 9.5]),
    "k": np.array([1.0, 8.0, 3.0, 3.0, 5.0]),
    "m": np.array([1.0, 16.0, 1024.0, 64.0, 2.0]),
}
for name in uspace:
    pe1 = _ParzenEstimator({name: uobs[name]}, {name: uspace[name]}, params(False))
    show(f"{name} weights", pe1._weights)
    show(f"{name} mus", pe1._mus[name])
    show(f"{name} sigmas", pe1._sigmas[name])
    pts = {"u": [0.0, 2.0, 5.5, 10.0], "k": [1.0, 3.0, 6.0, 8.0], "m": [1.0, 3.0, 100.0, 1024.0]}[name]
    show(f"{name} log_pdf", pe1.log_pdf({name: np.array(pts)}))

# Empty observations: only the prior kernel.
pe0 = _ParzenEstimator({"x": np.array([])}, {"x": FloatDistribution(-5.0, 5.0)}, params(True))
show("empty sigmas", pe0._sigmas["x"])
show("empty log_pdf", pe0.log_pdf({"x": np.array([0.0, 4.0])}))

# 30 observations: default_weights' ramp and the magic clip (univariate, many close values).
rng = np.random.RandomState(0)
o30 = np.round(rng.uniform(0, 1, 30), 3)
print("thirty", ", ".join(repr(float(v)) for v in o30))
pe30 = _ParzenEstimator({"x": o30}, {"x": FloatDistribution(0.0, 1.0)}, params(False))
show("thirty weights", pe30._weights)
show("thirty sigmas", pe30._sigmas["x"])
show("thirty log_pdf", pe30.log_pdf({"x": np.array([0.05, 0.5, 0.95])}))

# One TPE step on a study with pruned trials and a conditional parameter (multivariate=True):
# the relative space, the split, and the below/above estimators.
print("tpe step")
import warnings

from optuna.samplers._tpe.sampler import _get_observation_pairs, _split_observation_pairs
from optuna.samplers._tpe.sampler import default_gamma
from optuna.trial import TrialState, create_trial

warnings.simplefilter("ignore")
optuna.logging.set_verbosity(optuna.logging.WARNING)
dx = FloatDistribution(-5.0, 5.0)
dn = IntDistribution(1, 64, log=True)
dc = CategoricalDistribution(["a", "b", "c"])
study = optuna.create_study(direction="maximize")
for i in range(14):
    x = round(-4.5 + 0.7 * i, 3)
    n = [1, 2, 4, 8, 16, 32, 64][(3 * i) % 7]
    params = {"x": x, "n": n}
    dists = {"x": dx, "n": dn}
    if i % 3 == 0:
        params["c"] = ["a", "b", "c"][i % 2 * 2]  # "a" for even i, "c" for odd
        dists["c"] = dc
    value = -((x - 1.0) ** 2) - 0.1 * abs(np.log2(n) - 3)
    print(f"  trial {i}: x={x} n={n} c={params.get('c')} value={value!r}", end="")
    if i in (4, 9):  # pruned: reports at steps 1..(i//3), the last being the value
        inter = {s: value - 0.1 * (i // 3 - s) for s in range(1, i // 3 + 1)}
        t = create_trial(state=TrialState.PRUNED, params=params, distributions=dists,
                         intermediate_values=inter)
        print(f" PRUNED {inter}")
    else:
        t = create_trial(state=TrialState.COMPLETE, params=params, distributions=dists, value=value)
        print()
    study.add_trial(t)
sampler = optuna.samplers.TPESampler(multivariate=True, seed=0)
space = sampler.infer_relative_search_space(study, None)
print("  relative space:", sorted(space))
values, scores, _ = _get_observation_pairs(study, ["n", "x"], False, False)
below_idx, above_idx = _split_observation_pairs(scores, default_gamma(len(scores)), None)
print("  below:", list(below_idx), "above:", list(above_idx))
cv = {k: np.asarray(v, dtype=float) for k, v in values.items()}
pe_params = sampler._parzen_estimator_parameters
below = _ParzenEstimator({k: v[below_idx] for k, v in cv.items()}, space, pe_params)
above = _ParzenEstimator({k: v[above_idx] for k, v in cv.items()}, space, pe_params)
for label, pe in (("below", below), ("above", above)):
    show(f"{label} weights", pe._weights)
    for name in ("n", "x"):
        show(f"{label} {name} mus", pe._mus[name])
        show(f"{label} {name} sigmas", pe._sigmas[name])
pts = {"n": np.array([1.0, 8.0, 50.0]), "x": np.array([1.0, -4.0, 3.3])}
show("log l - log g", below.log_pdf(pts) - above.log_pdf(pts))
# The conditional parameter, sampled independently over the trials that have it.
values, scores, _ = _get_observation_pairs(study, ["c"], False, False)
below_idx, above_idx = _split_observation_pairs(scores, default_gamma(len(scores)), None)
c = np.asarray(values["c"], dtype=float)
bc, ac = c[below_idx][~np.isnan(c[below_idx])], c[above_idx][~np.isnan(c[above_idx])]
print("  c below:", list(bc), "c above:", list(ac))
below = _ParzenEstimator({"c": bc}, {"c": dc}, pe_params)
above = _ParzenEstimator({"c": ac}, {"c": dc}, pe_params)
show("c below weights", below._categorical_weights["c"].ravel())
show("c above weights", above._categorical_weights["c"].ravel())
show("c log l - log g", below.log_pdf({"c": np.array([0, 1, 2])}) - above.log_pdf({"c": np.array([0, 1, 2])}))
