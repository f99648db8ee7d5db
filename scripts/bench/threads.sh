#!/usr/bin/env bash
# How a run's speed scales with --threads (docs/benchmarks.md, "Threads"): the same training
# with each thread count in turn, A B A B ..., on classic control, Box2D, Bullet and SUMO
# workloads; prints each count's median wall time, steps/s and its speed-up over one thread.
# The runs' models are the same bits for every count (tests/runtime/test_cli_threads.cpp), so
# only the time differs.
#   scripts/bench/threads.sh                     # threads 1 and 2, 3 rounds
#   COUNTS="1 2 4 8" ROUNDS=5 scripts/bench/threads.sh [WORKLOAD...]
# Workloads: cartpole_ppo lunarlander_ppo gripper_ppo pendulum_sac traffic_network_ppo.
set -euo pipefail
cd "$(dirname "$0")/../.."
counts=${COUNTS:-"1 2"}
rounds=${ROUNDS:-3}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# name -> "experiment file | overrides": each a few seconds to a minute on one core.
workload() {
  case "$1" in
    cartpole_ppo) echo "configs/cartpole_ppo.yaml|env.n_envs=8 run.total_timesteps=65536" ;;
    lunarlander_ppo) echo "configs/cartpole_ppo.yaml|env.id=LunarLander-v3 env.n_envs=16 algo.n_steps=256 run.total_timesteps=65536" ;;
    gripper_ppo) echo "configs/cartpole_ppo.yaml|env.id=GripperLift-v0 env.n_envs=8 algo.n_steps=128 run.total_timesteps=8192" ;;
    pendulum_sac) echo "configs/pendulum_sac.yaml|run.total_timesteps=3000" ;;
    traffic_network_ppo) echo "configs/traffic_network_ppo.yaml|run.total_timesteps=2048" ;;
    *) echo "threads.sh: unknown workload $1" >&2; exit 2 ;;
  esac
}

names=("$@")
((${#names[@]})) || names=(cartpole_ppo lunarlander_ppo gripper_ppo pendulum_sac traffic_network_ppo)
printf '| workload | threads | wall s (median of %d) | env steps/s | speed-up |\n|---|---|---|---|---|\n' "$rounds"
for name in "${names[@]}"; do
  IFS='|' read -r config overrides <<<"$(workload "$name")"
  sets=()
  for o in $overrides; do sets+=(--set "$o"); done
  for ((r = 0; r < rounds; ++r)); do
    for t in $counts; do
      start=$(date +%s.%N)
      build/rlrun --threads "$t" train "$config" "${sets[@]}" --set run.out_dir="$out/runs" \
        --set run.name="$name" --set run.console_interval=1e9 >"$out/log" 2>&1 ||
        { cat "$out/log"; exit 1; }
      awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {print b - a}' >>"$out/$name.$t"
      steps=$(grep -oE "^trained [0-9]+ steps" "$out/log" | awk '{print $2}')
      rm -rf "$out/runs"
    done
  done
  base=""
  for t in $counts; do
    median=$(sort -g "$out/$name.$t" | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}')
    [[ -n "$base" ]] || base=$median
    awk -v n="$name" -v t="$t" -v m="$median" -v s="$steps" -v b="$base" \
      'BEGIN {printf "| %s | %s | %.2f | %.0f | %.2fx |\n", n, t, m, s / m, b / m}'
  done
done
