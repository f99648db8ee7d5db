#!/usr/bin/env bash
# Checks `rlrun export --format sb3` against the real Stable-Baselines3 2.4.1: SB3's load()
# opens every exported file with warnings as errors and its predict() gives rlrun's actions
# (tests/python/test_sb3_export.py, class Sb3LoadsExport; CI runs the rest of that file, which
# needs neither SB3 nor torch).
#   scripts/data/check_sb3_export.sh SB3_SRC GYMNASIUM_SRC [BUILD_DIR]
# SB3_SRC: a source tree of stable-baselines3 v2.4.1 (the dir holding stable_baselines3/);
# GYMNASIUM_SRC: one of Gymnasium v1.0.0 (the dir holding gymnasium/); BUILD_DIR: rlrun's build
# (default build/). Needs Debian 12's /usr/bin/python3 with python3-torch and
# python3-cloudpickle (apt-get), as scripts/data/make_sb3_models.sh does. SB3_CONTRIB_SRC (optional,
# from the environment): sb3-contrib v2.4.0's source tree, for MaskablePPO and RecurrentPPO.
set -euo pipefail
usage="usage: scripts/data/check_sb3_export.sh SB3_SRC GYMNASIUM_SRC [BUILD_DIR]"
[ $# -ge 2 ] || { echo "$usage" >&2; exit 2; }
[ -d "$1/stable_baselines3" ] || { echo "$usage: no stable_baselines3/ in '$1'" >&2; exit 2; }
[ -d "$2/gymnasium" ] || { echo "$usage: no gymnasium/ in '$2'" >&2; exit 2; }
here=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${3:-$here/build}" && pwd)
py=/usr/bin/python3
if ! "$py" -c 'import torch, cloudpickle' 2>/dev/null; then
    echo "$py cannot import torch/cloudpickle: install python3-torch python3-cloudpickle (apt-get)" >&2
    exit 1
fi
export SB3_SRC=$(cd "$1" && pwd) GYMNASIUM_SRC=$(cd "$2" && pwd)
export RLRUN_SOURCE_DIR=$here RLRUN_BINARY=$build/rlrun PYTHONPATH=$build/python
cd "$here/tests/python"
"$py" -m unittest -v test_sb3_export
