#!/usr/bin/env bash
# PPO with rl-zoo's CartPole-v1 settings (1e5 steps, 8 envs) on a pure-Python CartPole port
# (tests/python_envs/rlrun_test_envs/cartpole.py, one worker process per env, issue 17),
# against rlrun on its C++ CartPole-v1 and SB3's wall time for the same config (docs/benchmarks.md, "Anchors":
# 18.4 s, quiet machine). Whole processes, A B A B, median of SEEDS; prints a markdown table.
#   scripts/bench/python_train.sh            (after scripts/setup.sh)
#   SEEDS="1 2 3" PYTHON=/usr/bin/python3 scripts/bench/python_train.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
seeds=${SEEDS:-"1 2 3"}
python=${PYTHON:-/usr/bin/python3}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
zoo="algo: {id: PPO, n_steps: 32, batch_size: 256, n_epochs: 20, gamma: 0.98, gae_lambda: 0.8,
       learning_rate: lin_0.001, clip_range: lin_0.2, ent_coef: 0.0}"
cat >"$out/python.yaml" <<YAML
run: {name: python, seed: 1, total_timesteps: 100000, out_dir: $out/runs, console_interval: 1e9}
env: {id: "python:rlrun_test_envs.cartpole:CartPolePort", n_envs: 8, max_episode_steps: 500,
      python: $python}
$zoo
YAML
cat >"$out/native.yaml" <<YAML
run: {name: native, seed: 1, total_timesteps: 100000, out_dir: $out/runs, console_interval: 1e9}
env: {id: CartPole-v1, n_envs: 8}
$zoo
YAML
export PYTHONPATH=$PWD/tests/python_envs${PYTHONPATH:+:$PYTHONPATH}
# Wall seconds of one whole `rlrun train` process (start-up and worker start-up included).
wall() {
  local start end
  start=$(date +%s.%N)
  build/rlrun train "$1" --seed "$2" >"$out/log" 2>&1
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN {print b - a}'
}
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
py_times=() native_times=() returns=()
for seed in $seeds; do
  py_times+=("$(wall "$out/python.yaml" "$seed")")
  native_times+=("$(wall "$out/native.yaml" "$seed")")
  model=$(ls -d "$out"/runs/python/seed"$seed"*/model.zip | tail -1)
  returns+=("$(build/rlrun eval --model "$model" --episodes 10 --set env.id=python:rlrun_test_envs.cartpole:CartPolePort \
    --set env.python="$python" | sed -nE 's/.*mean_reward = ([-0-9.]+).*/\1/p')")
done
py=$(printf '%s\n' "${py_times[@]}" | median)
native=$(printf '%s\n' "${native_times[@]}" | median)
echo "| env | wall s (median of ${#py_times[@]}) | eval return per seed | SB3 wall s | speed-up vs SB3 |"
echo "|---|---|---|---|---|"
printf '| Python CartPole port, 8 worker processes | %.2f | %s | 18.4 | %.1fx |\n' "$py" "${returns[*]}" "$(awk -v t="$py" 'BEGIN {print 18.4 / t}')"
printf '| rlrun CartPole-v1 (C++), same config | %.2f | | 18.4 | %.1fx |\n' "$native" "$(awk -v t="$native" 'BEGIN {print 18.4 / t}')"
