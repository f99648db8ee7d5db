"""Summary of an `rlrun tune` study read with Optuna itself (scripts/bench/tune.sh).

  /usr/bin/python3 scripts/bench/tune_study_stats.py JOURNAL STUDY [THRESHOLD]

Prints the trial counts by state, the pruned fraction, the complete trials whose every seed
reached THRESHOLD (rlrun's user attribute rlrun:seed_values), the first such trial after the
random start-up trials, trial durations, the study's wall time and the best trial.
"""
import statistics
import sys
import warnings

import optuna

warnings.filterwarnings("ignore")
optuna.logging.set_verbosity(optuna.logging.ERROR)

journal, name = sys.argv[1], sys.argv[2]
threshold = float(sys.argv[3]) if len(sys.argv) > 3 else 475.0
study = optuna.load_study(study_name=name, storage=optuna.storages.JournalStorage(
    optuna.storages.JournalFileStorage(journal)))
trials = study.trials
count = {s: sum(t.state.name == s for t in trials) for s in ("COMPLETE", "PRUNED", "FAIL")}
good = [t for t in trials if t.state.name == "COMPLETE"
        and t.user_attrs.get("rlrun:seed_values")
        and all(v >= threshold for v in t.user_attrs["rlrun:seed_values"])]
finished = [t for t in trials if t.datetime_complete and t.datetime_start]
durations = [(t.datetime_complete - t.datetime_start).total_seconds() for t in finished]
wall = (max(t.datetime_complete for t in finished) - min(t.datetime_start for t in finished)).total_seconds()
print(f"trials: {len(trials)} ({count['COMPLETE']} complete, {count['PRUNED']} pruned "
      f"= {100 * count['PRUNED'] / max(len(trials), 1):.0f} %, {count['FAIL']} failed)")
print(f"complete trials with every seed >= {threshold:g}: {len(good)} "
      f"(first: trial {good[0].number if good else '-'}; first after the 10 random start-up trials: "
      f"{next((t.number for t in good if t.number >= 10), '-')})")
print(f"study wall time: {wall:.0f} s; trial time median {statistics.median(durations):.1f} s, "
      f"sum {sum(durations):.0f} s")
best = study.best_trial
print(f"best: trial {best.number}, value {best.value:g}, seeds {best.user_attrs.get('rlrun:seed_values')}")
