"""Optuna 3.1's samplers on the test functions of bench/tpe_bench.cpp, and the comparison table.

  /usr/bin/python3 scripts/bench/tpe.py run [--seeds 20] [--trials 100] [--samplers tpe,random]
                                             [--functions branin,hartmann6,noisy_quad]
      prints "function<TAB>optuna_<sampler><TAB>seed<TAB>best" lines, best being the true value
      of the best observed trial (as rlrun_tpe_bench does);
  /usr/bin/python3 scripts/bench/tpe.py table RESULTS...
      reads such lines (rlrun's and Optuna's) and prints a Markdown table: median best,
      interquartile range, and the two-sided Mann-Whitney U p-value of rlrun's sampler against
      Optuna's same sampler.

scripts/bench/tpe.sh runs both. Samplers: TPESampler(multivariate=True, seed=s) — rl-zoo's
setting, Optuna's other defaults (n_startup_trials=10, n_ei_candidates=24) — and
RandomSampler(seed=s). Mann-Whitney is written out here because Debian's python3 here has numpy
but no scipy: normal approximation with tie correction and continuity correction (scipy's
method="asymptotic"), adequate for 20 against 20.
"""
import argparse
import collections
import math
import sys
import warnings

import numpy as np


def branin(trial, rng):
    x1 = trial.suggest_float("x1", -5, 10)
    x2 = trial.suggest_float("x2", 0, 15)
    b, c, t = 5.1 / (4 * math.pi**2), 5 / math.pi, 1 / (8 * math.pi)
    v = (x2 - b * x1 * x1 + c * x1 - 6) ** 2 + 10 * (1 - t) * math.cos(x1) + 10
    return v, v


HARTMANN_ALPHA = np.array([1.0, 1.2, 3.0, 3.2])
HARTMANN_A = np.array(
    [[10, 3, 17, 3.5, 1.7, 8], [0.05, 10, 17, 0.1, 8, 14], [3, 3.5, 1.7, 10, 17, 8],
     [17, 8, 0.05, 10, 0.1, 14]])
HARTMANN_P = 1e-4 * np.array(
    [[1312, 1696, 5569, 124, 8283, 5886], [2329, 4135, 8307, 3736, 1004, 9991],
     [2348, 1451, 3522, 2883, 3047, 6650], [4047, 8828, 8732, 5743, 1091, 381]])


def hartmann6(trial, rng):
    x = np.array([trial.suggest_float(f"x{j}", 0, 1) for j in range(6)])
    v = -float(np.sum(HARTMANN_ALPHA * np.exp(-np.sum(HARTMANN_A * (x - HARTMANN_P) ** 2, axis=1))))
    return v, v


def noisy_quad(trial, rng):
    v = sum((trial.suggest_float(f"x{j}", -1, 1) - 0.3) ** 2 for j in range(4))
    return v + 0.01 * rng.standard_normal(), v


ORDER = {"tpe": 0, "tpe_univariate": 1, "random": 2}  # table rows: rlrun's, then Optuna's
FUNCTIONS = {"branin": branin, "hartmann6": hartmann6, "noisy_quad": noisy_quad}


def run(args):
    import optuna

    assert optuna.__version__.startswith("3.1."), optuna.__version__
    optuna.logging.set_verbosity(optuna.logging.WARNING)
    warnings.simplefilter("ignore", optuna.exceptions.ExperimentalWarning)
    for name in args.functions.split(","):
        function = FUNCTIONS[name]
        for sampler_name in args.samplers.split(","):
            for seed in range(args.seeds):
                if sampler_name == "tpe":
                    sampler = optuna.samplers.TPESampler(multivariate=True, seed=seed)
                elif sampler_name == "tpe_univariate":
                    sampler = optuna.samplers.TPESampler(seed=seed)
                elif sampler_name == "random":
                    sampler = optuna.samplers.RandomSampler(seed=seed)
                else:
                    sys.exit(f"unknown sampler {sampler_name}")
                study = optuna.create_study(sampler=sampler)
                noise = np.random.RandomState(seed + 1000)
                best_observed, best_truth = math.inf, math.inf
                for _ in range(args.trials):
                    trial = study.ask()
                    observed, truth = function(trial, noise)
                    study.tell(trial, observed)
                    if observed < best_observed:
                        best_observed, best_truth = observed, truth
                print(f"{name}\toptuna_{sampler_name}\t{seed}\t{best_truth:.10g}", flush=True)


def mann_whitney_p(x, y):
    """Two-sided Mann-Whitney U test p-value (normal approximation, tie and continuity
    corrected)."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    n1, n2 = len(x), len(y)
    both = np.concatenate([x, y])
    order = np.argsort(both, kind="stable")
    ranks = np.empty(len(both))
    sorted_values = both[order]
    i = 0
    ties = 0.0
    while i < len(both):  # average ranks over ties
        j = i
        while j + 1 < len(both) and sorted_values[j + 1] == sorted_values[i]:
            j += 1
        ranks[order[i : j + 1]] = 0.5 * (i + j) + 1
        t = j - i + 1
        ties += t**3 - t
        i = j + 1
    u1 = ranks[:n1].sum() - n1 * (n1 + 1) / 2
    n = n1 + n2
    mu = n1 * n2 / 2
    sigma = math.sqrt(n1 * n2 / 12 * ((n + 1) - ties / (n * (n - 1))))
    if sigma == 0:
        return 1.0
    z = (abs(u1 - mu) - 0.5) / sigma
    return min(1.0, math.erfc(max(z, 0.0) / math.sqrt(2)))


def table(args):
    results = collections.defaultdict(list)
    for path in args.results:
        with open(path) as f:
            for line in f:
                if line.strip():
                    function, sampler, _seed, best = line.split("\t")
                    results[(function, sampler)].append(float(best))
    print("| function | sampler | seeds | median best | IQR (25 % – 75 %) | p vs Optuna (Mann-Whitney) |")
    print("|---|---|---:|---:|---:|---:|")
    for function in FUNCTIONS:
        samplers = sorted({s for f, s in results if f == function},
                          key=lambda s: (ORDER.get(s.removeprefix("optuna_"), 9), s.startswith("optuna_")))
        for sampler in samplers:
            v = np.array(results[(function, sampler)])
            q25, q50, q75 = np.percentile(v, [25, 50, 75])
            p = "—"
            if not sampler.startswith("optuna_"):
                other = results.get((function, "optuna_" + sampler))
                if other:
                    p = f"{mann_whitney_p(v, other):.2f}"
            label = sampler if sampler.startswith("optuna_") else "rlrun_" + sampler
            print(f"| {function} | {label} | {len(v)} | {q50:.4g} | {q25:.4g} – {q75:.4g} | {p} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run")
    r.add_argument("--seeds", type=int, default=20)
    r.add_argument("--trials", type=int, default=100)
    r.add_argument("--samplers", default="tpe,random")
    r.add_argument("--functions", default=",".join(FUNCTIONS))
    t = sub.add_parser("table")
    t.add_argument("results", nargs="+")
    args = parser.parse_args()
    run(args) if args.command == "run" else table(args)


if __name__ == "__main__":
    main()
