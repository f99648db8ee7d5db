#!/usr/bin/env bash
# SAC on HalfCheetah-v4 with the zoo's settings: SB3 2.4.1 (Debian's torch) driving rlrun's
# HalfCheetah-v4 through the Python package (scripts/bench/sb3_mujoco.py) against `rlrun train`
# of configs/zoo/halfcheetah_sac.yaml, for the same env steps. Whole processes, A B A B, medians;
# prints wall seconds, env steps/s and the ratio (docs/benchmarks.md, "MuJoCo").
#   SB3_PYTHON=/path/to/venv/bin/python scripts/bench/sb3_mujoco.sh [STEPS] [REPS]
# STEPS defaults to 20000: 10000 random steps (learning_starts), then 10000 steps with an
# update each. SB3_PYTHON: an interpreter with stable_baselines3 2.4.1 and torch (not part of
# rlrun's setup; docs/benchmarks.md says how the one measured here was made). Debian's torch
# calls the system BLAS (libblas.so.3): Debian's default for it is OpenBLAS (6 GFLOP/s with the
# reference BLAS, 79 with OpenBLAS on this machine's 256x256 products), so SB3 runs with
# OpenBLAS's libblas first on its library path whatever the system's alternative says, and with
# torch and OpenBLAS on one thread, SB3's fastest setting here (docs/benchmarks.md, "Anchors").
set -euo pipefail
cd "$(dirname "$0")/../.."
steps=${1:-20000}
reps=${2:-3}
python=${SB3_PYTHON:?set SB3_PYTHON to a Python with stable_baselines3 and torch}
export PYTHONPATH=$PWD/build/python${PYTHONPATH:+:$PYTHONPATH}
openblas=/usr/lib/x86_64-linux-gnu/openblas-pthread
[[ -d $openblas ]] || { echo "sb3_mujoco: no $openblas (apt-get install libopenblas0-pthread)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
now() { date +%s.%N; }
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
sb3=() rlrun=()
for ((rep = 1; rep <= reps; rep++)); do
  t0=$(now)
  LD_LIBRARY_PATH=$openblas OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 \
    "$python" scripts/bench/sb3_mujoco.py "$steps" "$rep" >"$out/sb3.log" 2>&1
  t1=$(now)
  build/rlrun train configs/zoo/halfcheetah_sac.yaml --timesteps "$steps" --seed "$rep" \
    --out "$out/runs" >"$out/rlrun.log" 2>&1
  t2=$(now)
  sb3+=("$(awk -v a="$t0" -v b="$t1" 'BEGIN {print b - a}')")
  rlrun+=("$(awk -v a="$t1" -v b="$t2" 'BEGIN {print b - a}')")
done
s=$(printf '%s\n' "${sb3[@]}" | median)
r=$(printf '%s\n' "${rlrun[@]}" | median)
echo "| SAC HalfCheetah-v4, zoo settings, $steps env steps | SB3 $s s ($(awk -v n="$steps" -v t="$s" 'BEGIN {printf "%.0f", n / t}') steps/s) | rlrun $r s ($(awk -v n="$steps" -v t="$r" 'BEGIN {printf "%.0f", n / t}') steps/s) | $(awk -v a="$s" -v b="$r" 'BEGIN {printf "%.1fx", a / b}') |"
