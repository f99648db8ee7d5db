#!/usr/bin/env bash
# Issue 23's end-to-end measurement: `rlrun tune` with rl-zoo's PPO search space on CartPole-v1
# (configs/tune/cartpole_ppo_zoo.yaml: 100 trials, 2 seeds x 5e4 steps each, 10 evaluations,
# TPE, median pruner) with -j 2 workers; then the study read back with Optuna
# (scripts/bench/tune_study_stats.py): wall time, pruned fraction, trials reaching 475 in every seed.
#   scripts/bench/tune.sh                 (OUT=runs/bench_tune, JOBS=2)
set -euo pipefail
cd "$(dirname "$0")/../.."
RLRUN=${RLRUN:-build/rlrun}
OUT=${OUT:-runs/bench_tune}
JOBS=${JOBS:-2}
rm -rf "$OUT"
start=$(date +%s.%N)
mkdir -p "$OUT"
"$RLRUN" tune configs/tune/cartpole_ppo_zoo.yaml -j "$JOBS" --out "$OUT" >"$OUT/tune.log" 2>&1
took=$(echo "$(date +%s.%N) - $start" | bc)
journal=$OUT/study.journal
printf "rlrun tune -j %s: %.0f s wall\n" "$JOBS" "$took"
/usr/bin/python3 scripts/bench/tune_study_stats.py "$journal" cartpole_ppo_zoo 475
