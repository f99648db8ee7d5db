#!/usr/bin/env bash
# Issue 21's speed figures: simulated seconds per second of a whole TrafficNetwork-v0 episode
# (the 4x4 grid, 16 lights as agents choosing a phase every 5 s, max-pressure choosing) over
# libsumo and over traci, against plain `sumo` running the same scenario with its own programs
# (and the env with those same programs, "fixed-time": the same traffic as plain sumo, so the
# difference is the env's own cost);
# then training decisions per second (PPO, every light's decision counted). Runs alternate
# (sumo, rlrun libsumo, rlrun traci, ...) and the median of RUNS is printed.
#
#   scripts/bench/traffic_network_speed.sh                 # grid4x4, 3 runs each
#   SCENARIO=arterial4x4 RUNS=5 scripts/bench/traffic_network_speed.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
RLRUN=${RLRUN:-build/rlrun}
SCENARIO=${SCENARIO:-grid4x4}
RUNS=${RUNS:-3}
net=sumo_data/${SCENARIO%_peak}/${SCENARIO%_peak}.net.xml
routes=$(grep -m1 "^route_files:" "scenarios/$SCENARIO.yaml" | sed 's/.*\[\.\.\/\(.*\)\].*/\1/')

wall() {  # wall seconds of a command
  local start end
  start=$(date +%s.%N)
  "$@" >/dev/null 2>&1
  end=$(date +%s.%N)
  echo "$end - $start" | bc
}
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR + 1) / 2)]}'; }

declare -A times
kinds=("sumo" "libsumo" "libsumo, queue reward" "libsumo, fixed-time (no agent acts)" "traci" "traci, in rlrun's process")
for ((i = 0; i < RUNS; ++i)); do
  times[sumo]+="$(wall sumo -n "$net" -r "$routes" -b 0 -e 3600 --seed 1 --no-step-log)"$'\n'
  ev=("$RLRUN" eval --env TrafficNetwork-v0 --policy max-pressure --episodes 1 --seed 1
      --set "env.kwargs.scenario=scenarios/$SCENARIO.yaml")
  times[libsumo]+="$(wall "${ev[@]}" --set env.kwargs.backend=libsumo)"$'\n'
  times["libsumo, queue reward"]+="$(wall "${ev[@]}" --set env.kwargs.backend=libsumo --set env.kwargs.reward_fn=queue)"$'\n'
  times["libsumo, fixed-time (no agent acts)"]+="$(wall "${ev[@]/max-pressure/fixed-time}" --set env.kwargs.backend=libsumo)"$'\n'
  times[traci]+="$(wall "${ev[@]}" --set env.kwargs.backend=traci)"$'\n'
  times["traci, in rlrun's process"]+="$(wall "${ev[@]}" --set env.kwargs.backend=traci --set env.kwargs.own_process=false)"$'\n'
done
sumo_median=$(printf "%s" "${times[sumo]}" | median)
printf "| %s, 1 simulated hour | wall (median of %d) | simulated s / s | vs plain sumo |\n" "$SCENARIO" "$RUNS"
printf "|---|---|---|---|\n"
for kind in "${kinds[@]}"; do
  m=$(printf "%s" "${times[$kind]}" | median)
  printf "| %s | %.2f s | %.0f | %.0f %% |\n" "$kind" "$m" "$(echo "3600 / $m" | bc -l)" \
    "$(echo "100 * $sumo_median / $m" | bc -l)"
done

# Training: PPO (configs/traffic_network_ppo.yaml) for 2 simulated hours per env.
echo
printf "| training (PPO, %s) | timesteps/s = light decisions/s | env decisions/s |\n" "$SCENARIO"
printf "|---|---|---|\n"
out=$(mktemp -d)
for n in 1 2; do
  line=$("$RLRUN" train configs/traffic_network_ppo.yaml --set "env.kwargs.scenario=scenarios/$SCENARIO.yaml" \
         --set env.n_envs=$n --timesteps $((23040 * n)) --out "$out/$n" 2>&1 | grep "^trained")
  sps=$(echo "$line" | sed 's/.*(\([0-9.]*\) steps\/s).*/\1/')
  agents=16
  printf "| n_envs %d | %s | %.0f |\n" "$n" "$sps" "$(echo "$sps / $agents" | bc -l)"
done
rm -rf "$out"
