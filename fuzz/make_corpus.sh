#!/usr/bin/env bash
# Rebuilds the model, npy, export, journal, run_dir and sb3 seed corpora of the fuzz targets
# (fuzz/corpus/) from tiny runs of the rlrun binary and of Optuna (the config corpus is the
# shipped configs plus a few hand-written files). The journal seeds need Optuna 3.1 (PYTHON=...,
# default python3).
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
rm -f "$OUT"/model/* "$OUT"/npy/* "$OUT"/journal/* "$OUT"/run_dir/* "$OUT"/export/* "$OUT"/sb3/*
mkdir -p "$OUT/model" "$OUT/npy" "$OUT/config" "$OUT/journal" "$OUT/run_dir" "$OUT/export" \
  "$OUT/sb3"

# The SB3 corpus (fuzz_sb3.cpp) from the real SB3 files of tests/data/sb3: each space pickle
# (0x00 + it), each torch file of the smallest models (0x01 + it), every pickle of `data`
# (0x02 + it). Only Python's standard zip, json and base64 modules touch them: no unpickling.
python3 - "$OUT/sb3" <<'PY'
import base64, json, pathlib, sys, zipfile
out = pathlib.Path(sys.argv[1])
for case in sorted(pathlib.Path("tests/data/sb3").iterdir()):
    if not (case / "model.zip").exists() or case.name.startswith("evil"):
        continue
    with zipfile.ZipFile(case / "model.zip") as z:
        data = json.loads(z.read("data"))
        small = case.name in ("a2c_cartpole", "ppo_multi_input")
        for name in ("policy.pth", "pytorch_variables.pth") if small else ():
            (out / f"torch_{case.name}_{name}").write_bytes(b"\x01" + z.read(name))
    for key, value in data.items():
        if isinstance(value, dict) and ":serialized:" in value:
            pickle = base64.b64decode(value[":serialized:"])
            tag = b"\x00" if key.endswith("_space") else b"\x02"
            if len(pickle) <= 4096:
                (out / f"pickle_{case.name}_{key}").write_bytes(tag + pickle)
PY
ls "$OUT"/sb3 | wc -l | sed 's/^/sb3 seeds: /'


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
# RecurrentPPO: LSTM tensors, and the envs' LSTM states in the checkpoint's training state.
train recurrentppo 'run: {name: recurrentppo, seed: 1, total_timesteps: 64}
env: {id: CartPoleNoVel-v1, n_envs: 2}
algo: {id: RecurrentPPO, n_steps: 16, batch_size: 16, n_epochs: 1, policy: {lstm_hidden_size: 4, net_arch: [4]}}
checkpoint: {freq: 64}'

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
# The export corpus (fuzz_export.cpp): the exportable models (A2C's FrameStack is not), a Dict
# observation, and one with hostile meta.json strings.
train ppo_dict 'run: {name: ppo_dict, seed: 1, total_timesteps: 32}
env: {id: SimpleMultiObsEnv-v0}
algo: {id: PPO, n_steps: 16, batch_size: 16, n_epochs: 1, policy: {net_arch: [4]}}'
python3 fuzz/make_export_corpus.py "$OUT/export" "$WORK"/runs/{ppo,ppo_dict,dqn,sac,td3}/seed1/model.zip
ls "$OUT"/export | wc -l | sed 's/^/export seeds: /'

# The npy corpus: a few of each dtype is enough.
ls "$OUT/npy" | awk 'NR % 4 != 1' | sed "s|^|$OUT/npy/|" | xargs rm -f
ls -l "$OUT"/model | awk '{s += $5} END {print "model seeds:", NR - 1, "files,", s, "bytes"}'
ls "$OUT"/npy | wc -l | sed 's/^/npy seeds: /'

# The run-directory corpus (fuzz_run_dir.cpp): the tiny PPO run above as entries, and the same
# with the links, FIFOs and temporaries of docs/security.md's cases planted in it.
"${PYTHON:-python3}" - "$WORK/runs/ppo/seed1" "$OUT/run_dir" <<'PY'
import pathlib, sys
run, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
def entries(replace={}):
    parts = []
    for path in sorted(run.rglob("*")):
        rel = path.relative_to(run).as_posix()
        if path.name == ".lock":
            continue
        if rel in replace:
            parts.append(replace[rel])
        elif path.is_dir():
            parts.append(b"@@ dir " + rel.encode() + b"\n")
        else:
            parts.append(b"@@ file " + rel.encode() + b"\n" + path.read_bytes())
    return b"\n".join(parts)
(out / "whole_run").write_bytes(entries())
(out / "progress_only").write_bytes((run / "progress.csv").read_bytes())
(out / "log_link").write_bytes(entries({"log.txt": b"@@ link log.txt\nvictim"}))
(out / "progress_zero").write_bytes(entries({"progress.csv": b"@@ link progress.csv\nzero"}))
(out / "progress_fifo").write_bytes(entries({"progress.csv": b"@@ fifo progress.csv\n"}))
(out / "checkpoints_link").write_bytes(
    entries({"checkpoints": b"@@ link checkpoints\noutside"}) + b"\n@@ link config.yaml\nfifo")
(out / "stale_temporaries").write_bytes(
    entries() + b"\n@@ file .config.yaml.Ab12Cd.tmp\nhalf\n@@ file checkpoints/step_96.zip.tmp.Xy34Zw\nhalf")
# A per-agent run's team (runtime/io/agent_team_file.hpp): agents.json naming each agent's run
# directory; one team as written, one whose second agent's directory is a link out of the run.
team = (b'@@ file agents.json\n{"format": "rlrun agents", "version": 1, "env": "CartPole-v1", '
        b'"algorithm": "PPO", "agents": [{"name": "a", "run_dir": "agents/a"}, '
        b'{"name": "b", "run_dir": "agents/b"}]}\n'
        b"@@ file config.yaml\nrun: {name: team}\n@@ dir agents\n@@ dir agents/a\n"
        b"@@ file agents/a/model.zip\nPK\n")
(out / "agent_team").write_bytes(team + b"@@ dir agents/b\n@@ file agents/b/model.zip\nPK")
(out / "agent_team_link").write_bytes(team + b"@@ link agents/b\noutside")
PY
ls "$OUT"/run_dir | wc -l | sed 's/^/run_dir seeds: /'

# The journal corpus (fuzz_journal.cpp): study files as the two writers of the format write
# them. rlrun: a 3-trial study on CartPole PPO (a parameter of each kind, one conditional, the
# median pruner). Optuna 3.1 (JournalFileStorage): two studies with every distribution kind,
# every trial state, intermediate values with NaN and infinities, user attributes and an
# enqueued trial.
cat >"$WORK/study.yaml" <<EOF
name: small
base: $PWD/configs/cartpole_ppo.yaml
out_dir: $WORK/tune
storage: $WORK/rlrun_study.log
n_trials: 3
seeds_per_trial: 1
n_timesteps: 512
n_evaluations: 2
eval_episodes: 1
sampler: {type: tpe, seed: 3, n_startup_trials: 1}
pruner: {type: median, n_startup_trials: 1}
space:
  algo.learning_rate: {float: [1.0e-4, 3.0e-3], log: true}
  algo.n_epochs: {int: [1, 10]}
  algo.policy.net_arch: {categorical: [[32], [64, 64]]}
  algo.clip_range: {float: [0.1, 0.3], step: 0.1, if: {algo.n_epochs: [8, 9, 10]}}
EOF
"$RLRUN" tune "$WORK/study.yaml" >/dev/null
cp "$WORK/rlrun_study.log" "$OUT/journal/rlrun_study"
"${PYTHON:-python3}" - "$OUT/journal/optuna_studies" <<'PY'
import sys
import optuna
from optuna.storages import JournalFileStorage, JournalStorage
optuna.logging.set_verbosity(optuna.logging.WARNING)
storage = JournalStorage(JournalFileStorage(sys.argv[1]))
study = optuna.create_study(study_name="every_kind", storage=storage, direction="maximize",
                            sampler=optuna.samplers.RandomSampler(seed=1))
study.set_user_attr("note", "seed corpus")
study.enqueue_trial({"lr": 1e-3, "layers": 2})
def objective(trial):
    trial.suggest_float("lr", 1e-5, 1e-1, log=True)
    trial.suggest_float("clip", 0.1, 0.4, step=0.1)
    trial.suggest_float("plain", -1.0, 1.0)
    layers = trial.suggest_int("layers", 1, 4)
    trial.suggest_int("batch", 16, 256, log=True)
    trial.suggest_int("steps", 8, 64, step=8)
    trial.suggest_categorical("act", ["tanh", "relu", None, 3, 0.5, True])
    trial.set_user_attr("layers_seen", [layers, {"nested": "yes"}])
    for step, value in enumerate([1.0, float("nan"), float("inf"), -float("inf"), 2.5]):
        trial.report(value, step)
    if trial.number == 2:
        raise optuna.TrialPruned()
    if trial.number == 3:
        raise RuntimeError("a failed trial")
    return layers * 10.0 + trial.number
study.optimize(objective, n_trials=5, catch=(RuntimeError,))
running = study.ask()
running.suggest_float("lr", 1e-5, 1e-1, log=True)
running.report(0.5, 0)
other = optuna.create_study(study_name="minimize", storage=storage, direction="minimize")
other.optimize(lambda t: (t.suggest_float("x", -2, 2) - 1) ** 2, n_trials=3)
PY
ls "$OUT"/journal | wc -l | sed 's/^/journal seeds: /'
