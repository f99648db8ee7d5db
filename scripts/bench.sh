#!/usr/bin/env bash
# Training speed and the return reached, per config over seeds, beside SB3's wall time on the
# same machine kind (docs/benchmarks.md, "Anchors": quiet-machine medians).
#   scripts/bench.sh [--update-docs] [CONFIG...]    (default: every configs/*.yaml)
#   SEEDS="1 2 3" JOBS=1 scripts/bench.sh ...
# JOBS=1 (default) runs one training at a time on every CPU (rlrun's default --threads auto);
# JOBS=2 runs two trainings at once with --threads 1 each (faster to collect, slower per run).
# THREADS=N forces the per-run thread count. --update-docs replaces the table between the
# `bench:begin` / `bench:end` markers in docs/benchmarks.md.
set -euo pipefail
cd "$(dirname "$0")/.."
update_docs=0
if [[ "${1:-}" == "--update-docs" ]]; then update_docs=1; shift; fi
RLRUN_SKIP_INSTALL=${RLRUN_SKIP_INSTALL:-} scripts/setup.sh >/dev/null
configs=("$@")
# Default: every config but those marked `# bench: skip` (grasp_sac: 1e6 steps, hours; its
# speed is the [gripper_bench] line below).
((${#configs[@]})) || mapfile -t configs < <(grep -L '^# bench: skip' configs/*.yaml)
seeds=${SEEDS:-"1 2 3"}
jobs=${JOBS:-1}
threads=${THREADS:-$( ((jobs > 1)) && echo 1 || echo auto)}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# SB3 2.4.1 learn() wall seconds on this machine kind (docs/benchmarks.md, "Anchors"), by "ALGO ENV".
sb3_seconds() {
  case "$1" in
    "PPO CartPole-v1") echo 18.4 ;; "DQN CartPole-v1") echo 53.9 ;; "A2C CartPole-v1") echo 40.1 ;;
    "SAC Pendulum-v1") echo 237.6 ;; "TD3 Pendulum-v1") echo 116.7 ;; *) echo "" ;;
  esac
}

# One training + evaluation; writes "wall steps_per_s eval_mean eval_std" to $out/<name>.<seed>.
run_one() {
  local config=$1 seed=$2 name
  name=$(basename "$config" .yaml)
  local log summary model
  log=$(build/rlrun --threads "$threads" train "$config" --seed "$seed" --set run.out_dir="$out/runs" \
        --set run.name="$name" --set run.console_interval=1e9)
  summary=$(grep -E "^trained [0-9]+ steps in" <<<"$log" | tail -1)
  model=$(sed -E 's/.*model saved to (.*)$/\1/' <<<"$summary")
  # A config that evaluates during training keeps its best model and is scored by it (the zoo's
  # `enjoy.py --load-best`; such configs say so in their header), as in scripts/bench/seeds.sh.
  local scored=$model eval_line
  [[ -f "$(dirname "$model")/best_model.zip" ]] && scored=$(dirname "$model")/best_model.zip
  eval_line=$(build/rlrun eval --model "$scored" --episodes 10 | grep "mean_reward =")
  echo "$(awk '{print $2, $5}' <<<"$summary") $(sed -E 's/.*\(([0-9]+) steps\/s\).*/\1/' <<<"$summary") \
$(sed -E 's/.*mean_reward = ([-0-9.]+) \+\/- ([0-9.]+).*/\1 \2/' <<<"$eval_line")" >"$out/$name.$seed"
  cp "$(dirname "$model")/config.yaml" "$out/$name.config.yaml"
}
export -f run_one
export out threads

for config in "${configs[@]}"; do for seed in $seeds; do echo "$config $seed"; done; done |
  xargs -P "$jobs" -n 2 bash -c 'run_one "$0" "$1"'

median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }

table="| algo | env | timesteps | wall s (median) | env steps/s | eval return per seed (10 ep; the best model where kept) | SB3 wall s | speed-up |
|---|---|---|---|---|---|---|---|"
for config in "${configs[@]}"; do
  name=$(basename "$config" .yaml)
  algo=$(awk '/^algo:/{f=1} f&&/^  id:/{print $2; exit}' "$out/$name.config.yaml")
  env=$(awk '/^env:/{f=1} f&&/^  id:/{print $2; exit}' "$out/$name.config.yaml")
  steps=$(cat "$out/$name".[0-9]* | awk '{print $1}' | median)
  wall=$(cat "$out/$name".[0-9]* | awk '{print $2}' | median)
  rate=$(cat "$out/$name".[0-9]* | awk '{print $3}' | median)
  evals=$(for s in $seeds; do awk '{printf "%.1f ± %.1f", $4, $5}' "$out/$name.$s"; echo -n " / "; done | sed 's| / $||')
  sb3=$(sb3_seconds "$algo $env")
  speedup=""
  [[ -n "$sb3" ]] && speedup=$(awk -v a="$sb3" -v b="$wall" 'BEGIN {printf "%.1fx", a / b}')
  table+=$'\n'"| $algo | $env | $steps | $wall | $rate | $evals | ${sb3:-—} | ${speedup:-—} |"
done
# Video: `rlrun record` of a trained CartPole model, 2 episodes of 500 steps = 1002 frames at
# 600x400 (issue: under 2 s for 1000 frames). Best of 3, whole command (draw + ffmpeg).
record_line=""
cartpole_model=$(ls "$out"/runs/cartpole_ppo/seed*/model.zip 2>/dev/null | head -1 || true)
if [[ -n "$cartpole_model" ]] && command -v ffmpeg >/dev/null; then
  best=""
  for _ in 1 2 3; do
    start=$(date +%s.%N)
    build/rlrun record --model "$cartpole_model" --episodes 2 --output "$out/record.mp4" >/dev/null
    t=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {printf "%.2f", b - a}')
    best=$(awk -v a="${best:-1e9}" -v b="$t" 'BEGIN {print (b < a) ? b : a}')
  done
  frames=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames \
           -of csv=p=0 "$out/record.mp4")
  record_line="Video: \`rlrun record --model <cartpole_ppo model> --episodes 2\` writes $frames frames (600x400, H.264) in $best s (best of 3)."
fi
# Traffic: TrafficSignal-v0 over traci and libsumo against plain sumo, one simulated hour each
# (tests/envs/test_traffic_bench.cpp; issue 7: traci at least 70 % of plain sumo).
traffic_table=""
if command -v sumo >/dev/null; then
  traffic_table=$(build/tests/rlrun_tests "[traffic_bench]" | grep '^|' || true)
fi
# Grasp: GripperLift-v0 env steps/s on one core and SAC training steps/s on it
# (tests/envs/test_gripper_bench.cpp; issue 8: >= 3 000 env steps/s).
gripper_table=$(build/tests/rlrun_tests "[gripper_bench]" | grep '^|' || true)
# Box2D: LunarLander-v3 env steps/s on one core, random actions (tests/envs/test_lunar_lander.cpp).
lander_table=$(build/tests/rlrun_tests "[lunar_lander_bench]" | grep '^|' || true)
# Box2D: BipedalWalker-v3 / Hardcore env steps/s on one core (tests/envs/test_bipedal_walker.cpp).
walker_table=$(build/tests/rlrun_tests "[walker_bench]" | grep '^|' || true)
# Python: env steps/s of rlrun.make_vec("CartPole-v1", 64) from Python against a pure-Python
# CartPole loop (and Gymnasium's, when importable) (scripts/bench/python_env.py; issue 17).
python_table=""
if [[ -d build/python/rlrun ]]; then
  python_table=$(PYTHONPATH=build/python${PYTHONPATH:+:$PYTHONPATH} /usr/bin/python3 scripts/bench/python_env.py | grep '^|' || true)
fi
# Python envs in training: PPO zoo CartPole on a pure-Python CartPole port vs SB3 (issue 17).
python_train_table=$(scripts/bench/python_train.sh | grep '^|' || true)
# TensorBoard event files: their cost in a PPO CartPole run (issue 18: < 2 %).
tensorboard_table=$(scripts/bench/tensorboard.sh | grep -E '^(\||$)' || true)
machine="$(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), load $(cut -d' ' -f1-3 /proc/loadavg), JOBS=$jobs, threads=$threads, $(date -u +%Y-%m-%d)"
echo "$table"
echo
[[ -n "$record_line" ]] && echo "$record_line" && echo
[[ -n "$traffic_table" ]] && echo "$traffic_table" && echo
[[ -n "$gripper_table" ]] && echo "$gripper_table" && echo
[[ -n "$lander_table" ]] && echo "$lander_table" && echo
[[ -n "$walker_table" ]] && echo "$walker_table" && echo
[[ -n "$python_table" ]] && echo "$python_table" && echo
[[ -n "$python_train_table" ]] && echo "$python_train_table" && echo
[[ -n "$tensorboard_table" ]] && echo "$tensorboard_table" && echo
echo "machine: $machine"
if ((update_docs)); then
  block="$table"$'\n\n'"${record_line:+$record_line$'\n\n'}${traffic_table:+TrafficSignal-v0, one simulated hour of the shipped scenario:$'\n\n'$traffic_table$'\n\n'}${gripper_table:+GripperLift-v0 (Bullet):$'\n\n'$gripper_table$'\n\n'}${lander_table:+LunarLander-v3 (Box2D):$'\n\n'$lander_table$'\n\n'}${walker_table:+BipedalWalker (Box2D):$'\n\n'$walker_table$'\n\n'}${python_table:+Env steps from Python (scripts/bench/python_env.py):$'\n\n'$python_table$'\n\n'}${python_train_table:+PPO zoo CartPole on a Python env (scripts/bench/python_train.sh):$'\n\n'$python_train_table$'\n\n'}${tensorboard_table:+TensorBoard event files (scripts/bench/tensorboard.sh):$'\n\n'$tensorboard_table$'\n\n'}Measured by \`scripts/bench.sh\` on $machine."
  BLOCK="$block" python3 - <<'PY'
import os, re
path = "docs/benchmarks.md"
text = open(path).read()
new = "<!-- bench:begin -->\n" + os.environ["BLOCK"] + "\n<!-- bench:end -->"
text, n = re.subn(r"<!-- bench:begin -->.*?<!-- bench:end -->", lambda m: new, text, flags=re.S)
if n == 0:
    text += "\n## All configs (scripts/bench.sh)\n\n" + new + "\n"
open(path, "w").write(text)
PY
  echo "updated docs/benchmarks.md"
fi
