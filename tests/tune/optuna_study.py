"""Optuna's side of the journal interoperability tests (tests/tune/test_journal_storage.cpp).

  optuna_study.py dump JOURNAL STUDY        the study as Optuna loads it, as one JSON line
  optuna_study.py tools JOURNAL STUDY PNG    Optuna's own analysis on the study: parameter
                                            importances (its default fANOVA) and the
                                            optimisation history plot (matplotlib), as JSON
  optuna_study.py optimize JOURNAL STUDY N  N trials of a small problem, run by Optuna itself
                                            (TPE, median pruner, reports, a pruned and a
                                            failed trial), so rlrun can continue the study

Debian's python3-optuna (3.1); run with /usr/bin/python3.
"""
import json
import math
import sys
import warnings

import optuna

warnings.filterwarnings("ignore")
optuna.logging.set_verbosity(optuna.logging.ERROR)


def storage(path):
    return optuna.storages.JournalStorage(optuna.storages.JournalFileStorage(path))


def plain(value):
    if isinstance(value, float) and not math.isfinite(value):
        return repr(value)
    return value


def dump(path, name):
    study = optuna.load_study(study_name=name, storage=storage(path))
    trials = []
    for t in study.get_trials(deepcopy=False):
        trials.append({
            "number": t.number,
            "state": t.state.name,
            "params": {k: plain(v) for k, v in t.params.items()},
            "distributions": {k: optuna.distributions.distribution_to_json(d)
                              for k, d in t.distributions.items()},
            "intermediate_values": {str(k): plain(v) for k, v in t.intermediate_values.items()},
            "values": None if t.values is None else [plain(v) for v in t.values],
            "user_attrs": t.user_attrs,
            "system_attrs": t.system_attrs,
            "has_start": t.datetime_start is not None,
            "has_complete": t.datetime_complete is not None,
        })
    out = {"direction": study.direction.name, "user_attrs": study.user_attrs, "trials": trials}
    if any(t.state == optuna.trial.TrialState.COMPLETE for t in study.trials):
        out["best_number"] = study.best_trial.number
        out["best_value"] = study.best_value
    print(json.dumps(out, sort_keys=True))


def optimize(path, name, n):
    study = optuna.create_study(study_name=name, storage=storage(path), direction="minimize",
                                sampler=optuna.samplers.TPESampler(multivariate=True, seed=3),
                                pruner=optuna.pruners.MedianPruner(n_startup_trials=2),
                                load_if_exists=True)

    def objective(trial):
        x = trial.suggest_float("x", -5.0, 5.0)
        lr = trial.suggest_float("lr", 1e-5, 1e-1, log=True)
        layers = trial.suggest_int("layers", 1, 4)
        act = trial.suggest_categorical("act", ["tanh", "relu"])
        if trial.number == 3:
            raise RuntimeError("a failed trial")
        value = (x - 1.0) ** 2 + abs(math.log10(lr) + 3) + layers + (act == "relu")
        for step in range(3):
            trial.report(value + 3 - step, step)
            if trial.should_prune():
                raise optuna.TrialPruned()
        trial.set_user_attr("source", "optuna")
        return value

    study.optimize(objective, n_trials=n, catch=(RuntimeError,))


def tools(path, name, png):
    import matplotlib
    matplotlib.use("Agg")
    study = optuna.load_study(study_name=name, storage=storage(path))
    importances = optuna.importance.get_param_importances(study)
    axes = optuna.visualization.matplotlib.plot_optimization_history(study)
    axes.figure.savefig(png)
    print(json.dumps({"importances": importances, "best_params": study.best_params}))


if __name__ == "__main__":
    command = sys.argv[1]
    if command == "dump":
        dump(sys.argv[2], sys.argv[3])
    elif command == "tools":
        tools(sys.argv[2], sys.argv[3], sys.argv[4])
    elif command == "optimize":
        optimize(sys.argv[2], sys.argv[3], int(sys.argv[4]))
    else:
        sys.exit("unknown command " + command)
