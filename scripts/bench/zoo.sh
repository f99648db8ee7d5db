#!/usr/bin/env bash
# The rl-zoo entries (configs/zoo/, written by `rlrun zoo import`) trained with the zoo's own
# budgets, per seed, beside the zoo's published scores (rl-baselines3-zoo benchmark.md: mean and
# std of the return of its trained agent, deterministic, v2 landers).
#   scripts/bench/zoo.sh [CONFIG...]        (default: the classic-control and LunarLander entries)
#   SEEDS="1 2 3" JOBS=2 EPISODES=20 scripts/bench/zoo.sh ...
#   MODEL=best EVAL_FREQ=2000 scripts/bench/zoo.sh ...
# MODEL=best scores best_model.zip, the model the eval callback kept (rl-zoo's
# `enjoy.py --load-best`), where the run wrote one; EVAL_FREQ sets eval.freq (the imported files
# keep the zoo's 25 000 steps, which a 2e4-step entry never reaches).
# JOBS=2 (default) runs two trainings at once with --threads 1 each. Prints a Markdown table:
# each seed's mean return over EPISODES deterministic episodes (seeds 1000..), how many seeds are
# within the zoo's reported std of its mean (or above it), and the median wall time.
set -euo pipefail
cd "$(dirname "$0")/../.."
RLRUN_SKIP_INSTALL=${RLRUN_SKIP_INSTALL:-} scripts/setup.sh >/dev/null
configs=("$@")
if ((${#configs[@]} == 0)); then
  mapfile -t configs < <(ls configs/zoo/{cartpole,pendulum,mountaincar,mountaincarcontinuous,acrobot}_*.yaml \
                          configs/zoo/lunarlander_{ppo,dqn}.yaml)
fi
seeds=${SEEDS:-"1 2 3"}
jobs=${JOBS:-2}
episodes=${EPISODES:-20}
model_kind=${MODEL:-final}
eval_freq=${EVAL_FREQ:-}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# rl-zoo's published "mean std" (benchmark.md, 2024), by "algo env".
zoo_score() {
  case "$1" in
    "ppo CartPole-v1"|"a2c CartPole-v1"|"dqn CartPole-v1") echo "500.0 0.0" ;;
    "ppo Pendulum-v1") echo "-172.2 104.2" ;; "a2c Pendulum-v1") echo "-163.0 103.2" ;;
    "sac Pendulum-v1") echo "-157.0 88.7" ;; "td3 Pendulum-v1") echo "-151.9 90.2" ;;
    "ddpg Pendulum-v1") echo "-152.1 94.3" ;;
    "ppo MountainCar-v0") echo "-110.4 19.5" ;; "a2c MountainCar-v0") echo "-111.3 24.1" ;;
    "dqn MountainCar-v0") echo "-100.8 9.9" ;;
    "ppo MountainCarContinuous-v0") echo "88.3 2.6" ;; "a2c MountainCarContinuous-v0") echo "91.2 0.3" ;;
    "sac MountainCarContinuous-v0") echo "94.7 1.1" ;; "td3 MountainCarContinuous-v0") echo "93.5 0.1" ;;
    "ddpg MountainCarContinuous-v0") echo "93.5 0.0" ;;
    "ppo Acrobot-v1") echo "-73.5 18.2" ;; "a2c Acrobot-v1") echo "-83.4 17.2" ;;
    "dqn Acrobot-v1") echo "-76.6 11.8" ;;
    "ppo LunarLander-v3") echo "242.1 31.8" ;; "a2c LunarLander-v3") echo "155.8 80.4" ;;
    "dqn LunarLander-v3") echo "154.4 79.2" ;;
    "ppo LunarLanderContinuous-v3") echo "270.9 32.1" ;; "sac LunarLanderContinuous-v3") echo "260.4 65.5" ;;
    "td3 LunarLanderContinuous-v3") echo "207.5 67.6" ;; "ddpg LunarLanderContinuous-v3") echo "230.2 92.4" ;;
    "a2c LunarLanderContinuous-v3") echo "84.2 145.9" ;;
    "ppo BipedalWalker-v3") echo "287.9 2.4" ;; "a2c BipedalWalker-v3") echo "299.8 23.5" ;;
    "sac BipedalWalker-v3") echo "297.7 33.1" ;; "td3 BipedalWalker-v3") echo "306.0 56.9" ;;
    "ddpg BipedalWalker-v3") echo "197.5 141.6" ;;
    "tqc Pendulum-v1") echo "-151.3 87.9" ;; "tqc MountainCarContinuous-v0") echo "63.6 45.3" ;;
    "tqc LunarLanderContinuous-v3") echo "278.0 25.5" ;; "tqc BipedalWalker-v3") echo "329.8 45.1" ;;
    *) echo "" ;;
  esac
}

# One training + evaluation; writes "wall_seconds eval_mean" to $out/<name>.<seed>.
run_one() {
  local config=$1 seed=$2 name start end model eval_line
  name=$(basename "$config" .yaml)
  start=$(date +%s.%N)
  build/rlrun --threads 1 train "$config" --seed "$seed" --set run.out_dir="$out/runs" \
    --set run.name="$name" --set run.console_interval=1e9 ${eval_freq:+--set eval.freq=$eval_freq} \
    >"$out/$name.$seed.log" 2>&1
  end=$(date +%s.%N)
  model="$out/runs/$name/seed$seed/model.zip"
  if [[ $model_kind == best && -f "$out/runs/$name/seed$seed/best_model.zip" ]]; then
    model="$out/runs/$name/seed$seed/best_model.zip"
  fi
  eval_line=$(build/rlrun eval --model "$model" --episodes "$episodes" --seed 1000 | grep "mean_reward =")
  echo "$(echo "$end - $start" | bc) $(sed -E 's/.*mean_reward = ([-0-9.]+) .*/\1/' <<<"$eval_line")" \
    >"$out/$name.$seed"
}
export -f run_one
export out episodes model_kind eval_freq

for config in "${configs[@]}"; do for seed in $seeds; do echo "$config $seed"; done; done |
  xargs -P "$jobs" -n 2 bash -c 'run_one "$0" "$1"'

echo "| entry | steps | zoo score | return per seed ($episodes ep, $model_kind model) | seeds within zoo std | wall s (median, 1 thread) |"
echo "|---|---|---|---|---|---|"
for config in "${configs[@]}"; do
  name=$(basename "$config" .yaml)
  algo=$(awk '/^algo:/{f=1} f&&/^  id:/{print tolower($2); exit}' "$config")
  env=$(awk '/^env:/{f=1} f&&/^  id:/{print $2; exit}' "$config")
  steps=$(awk '/^  total_timesteps:/{print $2; exit}' "$config")
  read -r zoo_mean zoo_std <<<"$(zoo_score "$algo $env")" || true
  returns="" within=0 n=0 walls=""
  for seed in $seeds; do
    [[ -f "$out/$name.$seed" ]] || continue
    read -r wall ret <"$out/$name.$seed"
    returns+="${returns:+ / }$ret"; walls+="$wall"$'\n'; n=$((n + 1))
    if [[ -n "${zoo_mean:-}" ]] && awk -v r="$ret" -v m="$zoo_mean" -v s="$zoo_std" 'BEGIN{exit !(r >= m - s)}'; then
      within=$((within + 1))
    fi
  done
  median=$(printf "%s" "$walls" | sort -g | awk '{a[NR]=$1} END {if (NR) printf "%.1f", (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}')
  echo "| $algo $env | $steps | ${zoo_mean:-?} ± ${zoo_std:-?} | $returns | $within of $n | $median |"
done
