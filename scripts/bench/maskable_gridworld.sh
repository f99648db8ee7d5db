#!/usr/bin/env bash
# MaskablePPO against PPO on GridWorld-v0 (issue 45: masks learn with fewer steps). Both train
# configs/gridworld_maskable_ppo.yaml's hyperparameters, PPO with algo.id=PPO (the env's masks
# ignored); an evaluation every EVAL_FREQ steps (deterministic, from the start cell). Printed
# per seed: the first evaluation step whose return is the optimum (the shortest path:
# -(2 * (size - 1))), and after "/" the step from which every evaluation to the end of the
# budget is the optimum ("-": never). One Markdown row per grid size and algorithm, seeds
# 1..SEEDS, and the means over the seeds that got there.
#   scripts/bench/maskable_gridworld.sh            (SIZES="5 10" SEEDS=3 EVAL_FREQ=500 RLRUN=build/rlrun)
set -euo pipefail
cd "$(dirname "$0")/../.."
rlrun=${RLRUN:-build/rlrun}
seeds=${SEEDS:-3}
eval_freq=${EVAL_FREQ:-500}
sizes=${SIZES:-"5 10"}
[[ -x "$rlrun" ]] || { echo "maskable_gridworld: no rlrun binary at '$rlrun' (set RLRUN)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| grid | algorithm | budget | first optimal / optimal from then on, seeds 1..$seeds | means |"
echo "|---|---|---|---|---|"
for size in $sizes; do
  optimum=$((-2 * (size - 1)))
  budget=$((size <= 5 ? 20000 : 100000))
  for algo in MaskablePPO PPO; do
    row=()
    for seed in $(seq 1 "$seeds"); do
      name="grid${size}_${algo}"
      "$rlrun" train configs/gridworld_maskable_ppo.yaml --seed "$seed" --threads 1 \
        --set run.name="$name" --set run.out_dir="$out" --set algo.id="$algo" \
        --set run.total_timesteps="$budget" --set env.kwargs.size="$size" \
        --set env.kwargs.max_steps=$((size * size * 2)) \
        --set eval.freq="$eval_freq" --set eval.n_episodes=1 >/dev/null
      row+=("$(awk -F, -v opt="$optimum" '
        NR == 1 { next }
        $2 + 0 >= opt { if (first == "") first = $1; if (from == "") from = $1; next }
        { from = "" }
        END { print (first == "" ? "-" : first) "/" (from == "" ? "-" : from) }' \
        "$out/$name/seed$seed/evaluations.csv")")
    done
    means=$(printf '%s\n' "${row[@]}" | awk -F/ '
      $1 != "-" { a += $1; n++ } $2 != "-" { b += $2; m++ }
      END { print (n ? int(a / n) : "-") " / " (m ? int(b / m) : "-") }')
    echo "| ${size}x${size} | $algo | $budget | ${row[*]} | $means |"
  done
done
