"""Optuna's side of the importance comparison (tests/tune/test_param_importances.cpp).

  optuna_importances.py [SEED ...]

Builds the synthetic studies of the test — the same trials, drawn with the same SplitMix64
generator — and prints, per study and per seed of Optuna's FanovaImportanceEvaluator,
get_param_importances as one JSON line. The test holds these numbers as constants (so it needs
neither scikit-learn nor Optuna); rerun this after changing a study and update them.

Needs Debian's python3-optuna (3.1) and python3-sklearn; run with /usr/bin/python3.
"""
import json
import math
import sys
import warnings

import optuna
from optuna.distributions import CategoricalDistribution
from optuna.distributions import FloatDistribution
from optuna.distributions import IntDistribution

warnings.filterwarnings("ignore")
optuna.logging.set_verbosity(optuna.logging.ERROR)

MASK = (1 << 64) - 1


class SplitMix64:
    """Steele, Lea and Flood's SplitMix64, as tests/tune/synthetic_study.hpp."""

    def __init__(self, seed):
        self.state = seed & MASK

    def next(self):
        self.state = (self.state + 0x9E3779B97F4A7C15) & MASK
        z = self.state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
        return z ^ (z >> 31)

    def uniform(self):  # [0, 1), 53 bits
        return (self.next() >> 11) * (1.0 / (1 << 53))


def study_x1_only(rng):
    space = {name: FloatDistribution(0.0, 1.0) for name in ("x1", "x2", "x3")}
    params = {name: rng.uniform() for name in ("x1", "x2", "x3")}
    return space, params, math.sin(3.0 * params["x1"])


def study_x1_then_x2(rng):
    space = {name: FloatDistribution(0.0, 1.0) for name in ("x1", "x2", "x3")}
    params = {name: rng.uniform() for name in ("x1", "x2", "x3")}
    return space, params, params["x1"] + 0.3 * params["x2"]


def study_categorical(rng):
    choices = ("adam", "sgd", "rmsprop")
    space = {"optimizer": CategoricalDistribution(choices), "x": FloatDistribution(-1.0, 1.0)}
    index = min(int(rng.uniform() * 3), 2)
    x = -1.0 + 2.0 * rng.uniform()
    offset = (0.0, 2.0, 5.0)[index]
    return space, {"optimizer": choices[index], "x": x}, offset + 0.3 * x


def study_log(rng):
    space = {
        "learning_rate": FloatDistribution(1e-5, 1e-1, log=True),
        "gamma": FloatDistribution(0.9, 0.9999),
        "n_epochs": IntDistribution(1, 20),
    }
    lr = math.exp(math.log(1e-5) + rng.uniform() * (math.log(1e-1) - math.log(1e-5)))
    gamma = 0.9 + rng.uniform() * (0.9999 - 0.9)
    n_epochs = 1 + min(int(rng.uniform() * 20), 19)
    value = -((math.log10(lr) + 3.0) ** 2) + 10.0 * gamma + 0.01 * n_epochs
    return space, {"learning_rate": lr, "gamma": gamma, "n_epochs": n_epochs}, value


def study_log_raw_space(rng):
    # Optuna measures volumes in the parameters' own units, log ones too (transform_log=False):
    # learning rates below 3e-4 are most of the trials but 0.3 % of [1e-5, 0.1], so their step
    # explains less than x's slope.
    space = {"learning_rate": FloatDistribution(1e-5, 1e-1, log=True), "x": FloatDistribution(0, 1)}
    lr = math.exp(math.log(1e-5) + rng.uniform() * (math.log(1e-1) - math.log(1e-5)))
    x = rng.uniform()
    return space, {"learning_rate": lr, "x": x}, (1.0 if lr < 3e-4 else 0.0) + 0.3 * x


STUDIES = {
    "x1_only": study_x1_only,
    "x1_then_x2": study_x1_then_x2,
    "categorical": study_categorical,
    "log": study_log,
    "log_raw_space": study_log_raw_space,
}
N_TRIALS = 100


def build(name):
    rng = SplitMix64(12345)
    study = optuna.create_study()
    for _ in range(N_TRIALS):
        space, params, value = STUDIES[name](rng)
        study.add_trial(optuna.trial.create_trial(params=params, distributions=space, value=value))
    return study


def main():
    seeds = [int(s) for s in sys.argv[1:]] or [0]
    for name in STUDIES:
        study = build(name)
        for seed in seeds:
            evaluator = optuna.importance.FanovaImportanceEvaluator(seed=seed)
            importances = optuna.importance.get_param_importances(study, evaluator=evaluator)
            print(json.dumps({"study": name, "seed": seed, "importances": importances}))


if __name__ == "__main__":
    main()
