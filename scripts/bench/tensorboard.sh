#!/usr/bin/env bash
# What writing TensorBoard event files costs (issue 18: < 2 % of a PPO CartPole run): PPO with
# rl-zoo's CartPole-v1 settings (1e5 steps, 8 envs, 391 progress rows), whole `rlrun train`
# processes without and with --tensorboard-log, A B A B, PAIRS pairs; prints a markdown table
# with the median wall times, the median of the per-pair ratios and the event file's size;
# then the cost of one row measured inside the process (tests/runtime/test_tensorboard_log.cpp)
# and what the run's rows cost at that rate, which whole-process timing noise cannot resolve.
#   scripts/bench/tensorboard.sh              (after scripts/setup.sh)
#   PAIRS=9 scripts/bench/tensorboard.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
pairs=${PAIRS:-7}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cat >"$out/ppo.yaml" <<YAML
run: {name: ppo, seed: 1, total_timesteps: 100000, out_dir: $out/runs, console_interval: 1e9}
env: {id: CartPole-v1, n_envs: 8}
algo: {id: PPO, n_steps: 32, batch_size: 256, n_epochs: 20, gamma: 0.98, gae_lambda: 0.8,
       learning_rate: lin_0.001, clip_range: lin_0.2, ent_coef: 0.0}
YAML
# Wall seconds of one whole process.
wall() {
  local start end
  start=$(date +%s.%N)
  build/rlrun train "$out/ppo.yaml" "$@" >"$out/log" 2>&1
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN {print b - a}'
}
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
plain=() tb=() ratios=()
for _ in $(seq "$pairs"); do
  a=$(wall)
  b=$(wall --tensorboard-log "$out/tb")
  plain+=("$a") tb+=("$b")
  ratios+=("$(awk -v a="$a" -v b="$b" 'BEGIN {print b / a}')")
done
plain_s=$(printf '%s\n' "${plain[@]}" | median)
tb_s=$(printf '%s\n' "${tb[@]}" | median)
ratio=$(printf '%s\n' "${ratios[@]}" | median)
file=$(find "$out/tb" -name 'events.out.tfevents.*' | head -1)
rows=$(($(wc -l <"$(dirname "$(find "$out/runs" -name progress.csv | head -1)")/progress.csv") - 1))
echo "| PPO zoo CartPole 1e5 | without TensorBoard (median s) | with --tensorboard-log (median s) | median ratio of $pairs A/B pairs | event file |"
echo "|---|---|---|---|---|"
printf '| %s progress rows | %.2f | %.2f | %.3f (%+.1f %%) | %s bytes |\n' "$rows" "$plain_s" "$tb_s" "$ratio" \
  "$(awk -v r="$ratio" 'BEGIN {print (r - 1) * 100}')" "$(stat -c %s "$file")"
per_row=$(build/tests/rlrun_tests "[tensorboard_bench]" | grep '^|' | sed -E 's/.*\| ([0-9.]+) us \|/\1/')
echo
echo "| in-process cost | per row | $rows rows | share of the run without TensorBoard |"
echo "|---|---|---|---|"
awk -v us="$per_row" -v n="$rows" -v s="$plain_s" 'BEGIN {printf "| TensorBoardLog::write | %.1f us | %.2f ms | %.3f %% |\n", us, us * n / 1000, us * n / 1e4 / s}'
