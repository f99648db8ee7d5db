#!/usr/bin/env bash
# Single-observation latency of a deployed policy: rlrun::Policy::act (the embeddable library,
# through examples/embed_policy built against this build tree) against ONNX Runtime for
# Node.js on the exported ONNX file of the same model, for PPO CartPole (configs/cartpole_ppo.yaml,
# 64x64 tanh) and SAC Pendulum (configs/pendulum_sac.yaml's network). docs/benchmarks.md.
#   scripts/bench/deploy.sh [CALLS]        (default 100000)
set -euo pipefail
cd "$(dirname "$0")/../.."
RLRUN_SKIP_INSTALL=${RLRUN_SKIP_INSTALL:-} scripts/setup.sh >/dev/null
calls=${1:-100000}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cmake -S examples/embed_policy -B "$out/embed" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -Drlrun_DIR="$PWD/build" >/dev/null
cmake --build "$out/embed" >/dev/null
for config in cartpole_ppo:2048 pendulum_sac:300; do
  name=${config%%:*} steps=${config##*:}
  build/rlrun --threads 1 train "configs/$name.yaml" --timesteps "$steps" --set run.out_dir="$out/runs" \
    --set run.console_interval=1e9 >/dev/null
  model="$out/runs/$name/seed1/model.zip"
  build/rlrun export --model "$model" --output "$out/$name.onnx" >/dev/null
  obs_dim=$(build/rlrun export --model "$model" --format c --output "$out/$name.c" |
            sed -E 's/.*policy_act\(obs\[([0-9]+)\].*/\1/')
  echo "## $name"
  "$out/embed/embed_policy" "$model" --latency "$calls"
  NODE_PATH=build/onnxruntime/node_modules node scripts/bench/onnx_latency.js "$out/$name.onnx" "$calls" "$obs_dim"
done
