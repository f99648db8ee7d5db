#!/usr/bin/env bash
# Issue 21's learning benchmark: on each multi-intersection scenario, train the shared PPO
# policy (configs/traffic_network_ppo.yaml: 30 simulated hours) for each seed, then evaluate it
# and the three baselines on the same 5 evaluation hours (seeds 1000..1004), and print a table
# of mean_delay (RESCO's delay: mean tripinfo timeLoss), avg_waiting_time and throughput.
#
#   scripts/bench/traffic_network.sh                       # grid4x4 and arterial4x4, seeds 1 2 3
#   SCENARIOS="grid4x4_peak" SEEDS="1" TIMESTEPS=691200 scripts/bench/traffic_network.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
RLRUN=${RLRUN:-build/rlrun}
SCENARIOS=${SCENARIOS:-"grid4x4 arterial4x4"}
SEEDS=${SEEDS:-"1 2 3"}
CONFIG=${CONFIG:-configs/traffic_network_ppo.yaml}
TIMESTEPS=${TIMESTEPS:-}
OUT=${OUT:-runs/bench_traffic_network}
EPISODES=${EPISODES:-5}

metric() {  # metric NAME < eval output: the first "NAME = value" line's value
  grep -m1 " $1 = " | sed 's/.* = \([0-9.]*\).*/\1/'
}
evaluate() {  # evaluate ARGS...: "delay waiting throughput"
  local out
  out=$("$RLRUN" eval "$@" --episodes "$EPISODES" --seed 1000 2>&1)
  echo "$(metric mean_delay <<<"$out") $(metric avg_waiting_time <<<"$out") $(metric throughput <<<"$out")"
}

printf "| scenario | policy | mean_delay (s) | avg_waiting_time (s) | throughput | train time |\n"
printf "|---|---|---|---|---|---|\n"
for scenario in $SCENARIOS; do
  set_scenario="--set env.kwargs.scenario=scenarios/$scenario.yaml"
  for baseline in fixed-time actuated max-pressure; do
    read -r d w t <<<"$(evaluate --env TrafficNetwork-v0 --policy "$baseline" $set_scenario)"
    printf "| %s | %s | %s | %s | %s | |\n" "$scenario" "$baseline" "$d" "$w" "$t"
  done
  for seed in $SEEDS; do
    run_out="$OUT/$scenario"
    start=$(date +%s.%N)
    rm -rf "$run_out/$(grep -m1 "^  name:" "$CONFIG" | awk '{print $2}')/seed$seed"
    mkdir -p "$run_out"
    "$RLRUN" train "$CONFIG" $set_scenario --seed "$seed" ${TIMESTEPS:+--timesteps $TIMESTEPS} \
      --out "$run_out" >"$run_out.seed$seed.log" 2>&1
    took=$(echo "$(date +%s.%N) - $start" | bc)
    name=$(grep -m1 "^  name:" "$CONFIG" | awk '{print $2}')
    model="$run_out/$name/seed$seed/model.zip"
    read -r d w t <<<"$(evaluate --model "$model" $set_scenario)"
    printf "| %s | PPO seed %s | %s | %s | %s | %.0f s |\n" "$scenario" "$seed" "$d" "$w" "$t" "$took"
  done
done
