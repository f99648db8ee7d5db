#!/usr/bin/env bash
# A seed x learning-rate sweep in plain shell, for those who prefer it to `rlrun sweep`
# (docs/sweeps.md): every combination is one `rlrun train --set ...` process, JOBS at a time
# (xargs -P; GNU parallel works the same way), each on one core (--threads 1).
#   scripts/sweep.sh                                 # configs/cartpole_ppo.yaml, 2 rates x 3 seeds
#   CONFIG=configs/pendulum_sac.yaml RATES="1e-3 3e-4" SEEDS="1 2" JOBS=2 scripts/sweep.sh
#   TIMESTEPS=20000 OUT=runs/my_sweep scripts/sweep.sh
# Then: build/rlrun report "$OUT" and build/rlrun plot "$OUT" --output curves.png
# Unlike `rlrun sweep run`, re-running it trains everything again (in new seed<N>_2 directories).
set -euo pipefail
cd "$(dirname "$0")/.."
CONFIG=${CONFIG:-configs/cartpole_ppo.yaml}
RATES=${RATES:-"lin_0.001 lin_0.0003"}
SEEDS=${SEEDS:-"1 2 3"}
JOBS=${JOBS:-2}
OUT=${OUT:-runs/shell_sweep}
RLRUN=${RLRUN:-build/rlrun}
export CONFIG OUT RLRUN TIMESTEPS="${TIMESTEPS:-}"

for rate in $RATES; do
  for seed in $SEEDS; do
    echo "$rate $seed"
  done
done | xargs -P "$JOBS" -n 2 sh -c '
  rate=$0; seed=$1
  name=$(basename "$CONFIG" .yaml)_lr=$rate
  "$RLRUN" --threads 1 train "$CONFIG" --set algo.learning_rate="$rate" --set run.name="$name" \
    --seed "$seed" --out "$OUT" ${TIMESTEPS:+--timesteps "$TIMESTEPS"} >/dev/null 2>&1 \
    && echo "done: $name seed $seed" || { echo "FAILED: $name seed $seed" >&2; exit 1; }
'
