#!/usr/bin/env bash
# Issue 22's learning benchmark: each goal-task config trained for each seed, with HER and (with
# NOHER=1) the same run with the plain ReplayBuffer; per run the final model's success rate over
# 100 evaluation episodes (`rlrun eval --episodes 100 --seed 1000`), the first evaluation
# during training that reached the bar, the wall time and the training speed. Prints a
# Markdown table (docs/her.md).
#
#   scripts/bench/goal_tasks.sh                          # Reach (SAC, TQC), Push, PickAndPlace; seeds 1 2 3
#   CONFIGS="gripper_reach_sac_her" SEEDS="1" NOHER=1 scripts/bench/goal_tasks.sh
#
# Push and PickAndPlace take ~35-60 min per seed on this 2-core machine (docs/her.md).
set -euo pipefail
cd "$(dirname "$0")/../.."
RLRUN=${RLRUN:-build/rlrun}
CONFIGS=${CONFIGS:-"gripper_reach_sac_her gripper_reach_tqc_her gripper_push_sac_her gripper_pick_and_place_sac_her"}
SEEDS=${SEEDS:-"1 2 3"}
NOHER=${NOHER:-0}
OUT=${OUT:-runs/bench_goal_tasks}

bar() {  # the issue's success bar for a config
  case "$1" in
    *reach*) echo 0.95 ;;
    *push*) echo 0.8 ;;
    *) echo 0.7 ;;
  esac
}
# The success_rate column of evaluations.csv (task metrics may follow it): the first row at or
# above the bar ("-" if none).
first_at_bar() {
  awk -F, -v bar="$2" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "success_rate") c = i; next }
                       $c >= bar { print $1; found = 1; exit } END { if (!found) print "-" }' "$1"
}

printf "| config | buffer | seed | success (100 episodes) | first eval >= bar at step | wall time | steps/s |\n"
printf "|---|---|---|---|---|---|---|\n"
for config in $CONFIGS; do
  buffers="HerReplayBuffer"
  [ "$NOHER" = 1 ] && buffers="HerReplayBuffer ReplayBuffer"
  for buffer in $buffers; do
    for seed in $SEEDS; do
      out="$OUT/$buffer"
      mkdir -p "$out"
      rm -rf "$out/$config/seed$seed"
      start=$(date +%s.%N)
      "$RLRUN" train "configs/$config.yaml" --seed "$seed" --out "$out" \
        --set "algo.replay_buffer_class=$buffer" >"$out/$config.seed$seed.log" 2>&1
      took=$(echo "$(date +%s.%N) - $start" | bc)
      run="$out/$config/seed$seed"
      steps=$(grep -o "trained [0-9]* steps" "$out/$config.seed$seed.log" | awk '{print $2}')
      success=$("$RLRUN" eval --model "$run/model.zip" --episodes 100 --seed 1000 2>&1 |
                grep -o "success_rate = [0-9.]*" | awk '{print $3}')
      printf "| %s | %s | %s | %s | %s | %.0f s | %.0f |\n" "$config" "$buffer" "$seed" "$success" \
        "$(first_at_bar "$run/evaluations.csv" "$(bar "$config")")" "$took" "$(echo "$steps / $took" | bc -l)"
    done
  done
done
