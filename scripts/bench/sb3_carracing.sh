#!/usr/bin/env bash
# PPO with the zoo's CarRacing-v3 settings (CnnPolicy, 8 envs, FrameSkip 2, 64x64 gray, 2 frames,
# reward normalisation, gSDE): SB3 2.4.1 (Debian's torch) driving rlrun's CarRacing-v3 through the
# Python package (scripts/bench/sb3_carracing.py) against `rlrun train
# configs/zoo/carracing_ppo.yaml`, for the same env steps, evaluation off. Whole processes, A B A
# B; prints the median wall seconds, env steps/s, the largest resident memory (GNU time's max RSS)
# and the ratios (docs/benchmarks.md, "CarRacing-v3").
#   SB3_PYTHON=/path/to/python scripts/bench/sb3_carracing.sh [STEPS] [REPS]
# STEPS defaults to 8192 (two PPO updates of 8 x 512). SB3_PYTHON: an interpreter with
# stable_baselines3 2.4.1, torch, Gymnasium 1.0 and cv2 (not part of rlrun's setup). SB3 runs
# with OpenBLAS first on its library path and one torch thread, as in scripts/bench/sb3_mujoco.sh.
set -euo pipefail
cd "$(dirname "$0")/../.."
steps=${1:-8192}
reps=${2:-2}
python=${SB3_PYTHON:?set SB3_PYTHON to a Python with stable_baselines3, torch and cv2}
export PYTHONPATH=$PWD/build/python${PYTHONPATH:+:$PYTHONPATH}
openblas=/usr/lib/x86_64-linux-gnu/openblas-pthread
[[ -d $openblas ]] || { echo "sb3_carracing: no $openblas (apt-get install libopenblas0-pthread)" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "sb3_carracing: no /usr/bin/time (apt-get install time)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
# GNU time's "Elapsed (wall clock)" as seconds, and "Maximum resident set size" in MB.
wall() { awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, p, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + p[i]; print s}' "$1"; }
rss() { awk -F': ' '/Maximum resident set size/ {printf "%.0f\n", $2 / 1024}' "$1"; }
sb3_s=() sb3_mb=() rlrun_s=() rlrun_mb=()
for ((rep = 1; rep <= reps; rep++)); do
  LD_LIBRARY_PATH=$openblas OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 /usr/bin/time -v -o "$out/sb3.time" \
    "$python" scripts/bench/sb3_carracing.py "$steps" "$rep" >"$out/sb3.log" 2>&1 ||
    { cat "$out/sb3.log" >&2; exit 1; }
  /usr/bin/time -v -o "$out/rlrun.time" build/rlrun train configs/zoo/carracing_ppo.yaml \
    --timesteps "$steps" --seed "$rep" --set eval.freq=0 --out "$out/runs" >"$out/rlrun.log" 2>&1 ||
    { cat "$out/rlrun.log" >&2; exit 1; }
  sb3_s+=("$(wall "$out/sb3.time")") sb3_mb+=("$(rss "$out/sb3.time")")
  rlrun_s+=("$(wall "$out/rlrun.time")") rlrun_mb+=("$(rss "$out/rlrun.time")")
done
s=$(printf '%s\n' "${sb3_s[@]}" | median) r=$(printf '%s\n' "${rlrun_s[@]}" | median)
sm=$(printf '%s\n' "${sb3_mb[@]}" | median) rm=$(printf '%s\n' "${rlrun_mb[@]}" | median)
echo "| PPO CnnPolicy CarRacing-v3, zoo settings, $steps env steps | SB3 $s s ($(awk -v n="$steps" -v t="$s" 'BEGIN {printf "%.0f", n / t}') steps/s), $sm MB | rlrun $r s ($(awk -v n="$steps" -v t="$r" 'BEGIN {printf "%.0f", n / t}') steps/s), $rm MB | $(awk -v a="$s" -v b="$r" 'BEGIN {printf "%.1fx", a / b}') faster, $(awk -v a="$sm" -v b="$rm" 'BEGIN {printf "%.2f", b / a}') of the memory |"
