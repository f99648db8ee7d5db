#!/usr/bin/env bash
# Rebuilds the model and npy seed corpora of the fuzz targets (fuzz/corpus/) from tiny runs of
# the rlrun binary (the config corpus is the shipped configs plus a few hand-written files).
#   fuzz/make_corpus.sh [path/to/rlrun]      (default: build/rlrun)
# Each model file becomes two seeds (fuzz_model.cpp): "raw_*" (0x00 + the zip) and "list_*"
# (0x01 + its members, stored). Seeds are kept tiny (4-unit layers, 16-transition buffers) so
# that mutations stay cheap.
set -euo pipefail
cd "$(dirname "$0")/.."
RLRUN=$(realpath "${1:-build/rlrun}")
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
OUT=fuzz/corpus
rm -f "$OUT"/model/* "$OUT"/npy/*
mkdir -p "$OUT/model" "$OUT/npy" "$OUT/config"

train() {  # name config-text
  printf '%s\n' "$2" > "$WORK/$1.yaml"
  "$RLRUN" train "$WORK/$1.yaml" --set run.out_dir="$WORK/runs" >/dev/null
}
train ppo 'run: {name: ppo, seed: 1, total_timesteps: 64}
env: {id: CartPole-v1, n_envs: 2, wrappers: [{id: NormalizeObservation}]}
algo: {id: PPO, n_steps: 16, batch_size: 16, n_epochs: 1, policy: {net_arch: [4]}}
checkpoint: {freq: 64}'
train dqn 'run: {name: dqn, seed: 1, total_timesteps: 64}
env: {id: GridWorld-v0, wrappers: [{id: OneHotObservation}]}
algo: {id: DQN, buffer_size: 16, learning_starts: 8, batch_size: 4, policy: {net_arch: [4]}}
checkpoint: {freq: 64}'
train sac 'run: {name: sac, seed: 1, total_timesteps: 32}
env: {id: Pendulum-v1, wrappers: [{id: NormalizeReward}]}
algo: {id: SAC, buffer_size: 16, learning_starts: 8, batch_size: 4, policy: {net_arch: [4]}}
checkpoint: {freq: 32}'
train td3 'run: {name: td3, seed: 1, total_timesteps: 32}
env: {id: MountainCarContinuous-v0}
algo: {id: TD3, buffer_size: 16, learning_starts: 8, batch_size: 4, policy: {net_arch: [4]}}'
train a2c 'run: {name: a2c, seed: 1, total_timesteps: 40}
env: {id: Acrobot-v1, wrappers: [{id: FrameStack, n_stack: 2}]}
algo: {id: A2C, n_steps: 5, policy: {net_arch: [4]}}'

python3 - "$WORK/runs" "$OUT" <<'PY'
import pathlib, struct, sys, zipfile
runs, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
for path in sorted(runs.glob("*/seed1/model.zip")) + sorted(runs.glob("*/seed1/checkpoints/*.zip")):
    algo = path.parts[-3] if path.name == "model.zip" else path.parts[-4]
    tag = f"{algo}_{'model' if path.name == 'model.zip' else 'checkpoint'}"
    (out / "model" / f"raw_{tag}").write_bytes(b"\x00" + path.read_bytes())
    listing = bytearray(b"\x01")
    with zipfile.ZipFile(path) as z:
        for info in z.infolist():
            data = z.read(info)
            name = info.filename.encode()
            listing += bytes([len(name)]) + name + b"\x00" + struct.pack("<H", len(data)) + data
            if path.name == "model.zip" and name.endswith(b".npy"):
                short = name.decode().replace("/", "_")
                (out / "npy" / f"{algo}_{short}").write_bytes(data)
    (out / "model" / f"list_{tag}").write_bytes(bytes(listing))
PY
# The npy corpus: a few of each dtype is enough.
ls "$OUT/npy" | awk 'NR % 4 != 1' | sed "s|^|$OUT/npy/|" | xargs rm -f
ls -l "$OUT"/model | awk '{s += $5} END {print "model seeds:", NR - 1, "files,", s, "bytes"}'
ls "$OUT"/npy | wc -l | sed 's/^/npy seeds: /'
