#!/usr/bin/env bash
# Writes tests/data/sb3/: small models trained and saved by the real Stable-Baselines3 2.4.1
# (PPO, A2C, DQN, SAC, TD3, DDPG on CartPole-v1 / Pendulum-v1, PPO MultiInputPolicy on a Dict env),
# each with 1000 reference observations, SB3's deterministic actions for them and per-seed episode
# returns, plus two deliberately malicious model.zip files for the loader's security tests
# (scripts/data/make_sb3_models.py says what each file is).
#   scripts/data/make_sb3_models.sh [SB3_SRC GYMNASIUM_SRC] [CASE...]
# SB3_SRC: a source tree of stable-baselines3 v2.4.1 (the dir holding stable_baselines3/);
# GYMNASIUM_SRC: one of Gymnasium v1.0.0 (the dir holding gymnasium/). Either may come from the
# environment variables of the same name instead. Needs Debian 12's /usr/bin/python3 with its
# python3-torch (1.13.1), python3-cloudpickle, python3-numpy, python3-pandas, python3-matplotlib.
# The outputs are committed, so building and running the tests never needs torch or SB3.
set -euo pipefail
sb3=${SB3_SRC:-}
gymsrc=${GYMNASIUM_SRC:-}
if [ $# -ge 2 ] && [ -d "$1" ]; then  # directories given on the command line win
    sb3=$1 gymsrc=$2
    shift 2
fi
# Any further arguments are case names (e.g. ppo_cartpole) to remake just those.
usage="usage: scripts/data/make_sb3_models.sh SB3_SRC GYMNASIUM_SRC (or set SB3_SRC / GYMNASIUM_SRC)"
[ -n "$sb3" ] && [ -d "$sb3/stable_baselines3" ] || { echo "$usage: no stable_baselines3/ in '$sb3'" >&2; exit 2; }
[ -n "$gymsrc" ] && [ -d "$gymsrc/gymnasium" ] || { echo "$usage: no gymnasium/ in '$gymsrc'" >&2; exit 2; }
py=/usr/bin/python3
if ! "$py" -c 'import torch, cloudpickle' 2>/dev/null; then
    echo "$py cannot import torch/cloudpickle: install python3-torch python3-cloudpickle (apt-get)" >&2
    exit 1
fi
here=$(cd "$(dirname "$0")/../.." && pwd)
sb3=$(cd "$sb3" && pwd)
gymsrc=$(cd "$gymsrc" && pwd)
# Gymnasium imports farama_notifications (a one-line PyPI package) only to print release notes;
# a stub stands in for it if it is not installed.
stub=$(mktemp -d)
trap 'rm -rf "$stub"' EXIT
if ! "$py" -c 'import farama_notifications' 2>/dev/null; then
    echo 'notifications = {}' >"$stub/farama_notifications.py"
fi
# SB3_CONTRIB_SRC (optional): a source tree of sb3-contrib v2.4.0 (the dir holding
# sb3_contrib/), for the QR-DQN and TQC cases; without it those cases are left as they are.
contrib=""
if [ -n "${SB3_CONTRIB_SRC:-}" ]; then
    [ -d "$SB3_CONTRIB_SRC/sb3_contrib" ] || { echo "no sb3_contrib/ in '$SB3_CONTRIB_SRC'" >&2; exit 2; }
    contrib="$(cd "$SB3_CONTRIB_SRC" && pwd):"
fi
export PYTHONPATH="$contrib$sb3:$gymsrc:$stub${PYTHONPATH:+:$PYTHONPATH}"
"$py" -c 'import stable_baselines3 as s, gymnasium as g; assert s.__version__ == "2.4.1", s.__version__; assert g.__version__ == "1.0.0", g.__version__'
"$py" "$here/scripts/data/make_sb3_models.py" "$here/tests/data/sb3" "$@"
