#!/usr/bin/env bash
# The MuJoCo learning benchmarks of docs/mujoco.md: SAC on HalfCheetah-v4 and TD3 on Hopper-v4
# with the zoo's settings for 3e5 steps (configs/halfcheetah_sac.yaml, configs/hopper_td3.yaml),
# seeds 1-5. Each run evaluates every 25 000 steps (5 deterministic episodes, the zoo's
# protocol); the score is the last evaluation's mean return. Prints a markdown table (returns per
# seed, how many reach the bar: HalfCheetah >= 5000, Hopper >= 2500, wall time) and, with
# matplotlib, draws the learning curves to docs/images/mujoco_curves.png.
#   scripts/bench/mujoco.sh [CONFIG...]      SEEDS="1 2 3 4 5" THREADS=2 OUT=DIR
# About 25-35 minutes a run on 2 quiet cores (3e5 gradient steps on 256x256 or 400x300).
set -euo pipefail
cd "$(dirname "$0")/../.."
configs=("$@")
((${#configs[@]})) || configs=(configs/halfcheetah_sac.yaml configs/hopper_td3.yaml)
seeds=${SEEDS:-"1 2 3 4 5"}
threads=${THREADS:-2}
out=${OUT:-$(mktemp -d)}
declare -A bar=([halfcheetah_sac]=5000 [hopper_td3]=2500)
echo "| config | seeds | final evaluation (mean of 5 episodes) per seed | reaching the bar | wall s per run |"
echo "|---|---|---|---|---|"
for config in "${configs[@]}"; do
  name=$(basename "$config" .yaml)
  returns=() reached=0 walls=()
  for seed in $seeds; do
    start=$(date +%s.%N)
    build/rlrun train "$config" --seed "$seed" --threads "$threads" --out "$out" >"$out/$name.$seed.log" 2>&1
    walls+=("$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {printf "%.0f", b - a}')")
    final=$(tail -1 "$out/$name/seed$seed/evaluations.csv" | cut -d, -f2)
    returns+=("$final")
    awk -v r="$final" -v b="${bar[$name]:-0}" 'BEGIN {exit !(r >= b)}' && reached=$((reached + 1))
  done
  echo "| $name | $seeds | ${returns[*]} | $reached of ${#returns[@]} (>= ${bar[$name]:-?}) | ${walls[*]} |"
done
python3 - "$out" "${configs[@]}" <<'PY' || echo "(no learning curves: matplotlib missing)" >&2
import csv, os, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
out, configs = sys.argv[1], sys.argv[2:]
fig, axes = plt.subplots(1, len(configs), figsize=(6 * len(configs), 4), squeeze=False)
for ax, config in zip(axes[0], configs):
    name = os.path.basename(config)[:-5]
    for seed in sorted(os.listdir(os.path.join(out, name))):
        rows = list(csv.DictReader(open(os.path.join(out, name, seed, "evaluations.csv"))))
        ax.plot([int(r["timesteps"]) for r in rows], [float(r["mean_reward"]) for r in rows], label=seed)
    ax.set_title(name); ax.set_xlabel("env steps"); ax.set_ylabel("evaluation return"); ax.legend()
fig.tight_layout()
fig.savefig("docs/images/mujoco_curves.png", dpi=80)
PY
