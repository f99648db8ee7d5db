#!/usr/bin/env bash
# Measures training speed and the return reached, for each config and seed:
#   scripts/bench.sh [CONFIG...]          (default: configs/cartpole_ppo.yaml)
#   SEEDS="1 2 3" scripts/bench.sh ...
# Prints a Markdown table (wall s, env steps/s, final 10-episode deterministic evaluation) to
# paste into docs/benchmarks.md. Runs one training at a time, on one core (the networks are
# single-threaded), so that numbers are comparable with ../shared/reference/anchors.md.
set -euo pipefail
cd "$(dirname "$0")/.."
RLRUN_SKIP_INSTALL=${RLRUN_SKIP_INSTALL:-} scripts/setup.sh >/dev/null
configs=("$@")
((${#configs[@]})) || configs=(configs/cartpole_ppo.yaml)
seeds=${SEEDS:-"1 2 3"}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

echo "| config | seed | timesteps | wall s | env steps/s | eval return (10 ep) |"
echo "|---|---|---|---|---|---|"
for config in "${configs[@]}"; do
  for seed in $seeds; do
    log=$(build/rlrun train "$config" --seed "$seed" --set run.out_dir="$out" --set run.console_interval=1e9)
    summary=$(grep -E "^trained [0-9]+ steps in" <<<"$log" | tail -1)
    steps=$(awk '{print $2}' <<<"$summary")
    wall=$(awk '{print $5}' <<<"$summary")
    rate=$(sed -E 's/.*\(([0-9]+) steps\/s\).*/\1/' <<<"$summary")
    model=$(sed -E 's/.*model saved to (.*)$/\1/' <<<"$summary")
    eval=$(build/rlrun eval --model "$model" --episodes 10 | sed -E 's/.*mean_reward = ([-0-9.]+ \+\/- [0-9.]+).*/\1/')
    echo "| $(basename "$config" .yaml) | $seed | $steps | $wall | $rate | $eval |"
  done
done
echo
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), load $(cut -d' ' -f1-3 /proc/loadavg), $(date -u +%Y-%m-%d)"
