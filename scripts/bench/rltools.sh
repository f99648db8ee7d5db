#!/usr/bin/env bash
# RLtools' Pendulum-v1 zoo (SAC, TD3, PPO) beside rlrun running the same hyperparameters
# (configs/rltools/): wall time to RLtools' step budget and the final return over 100
# deterministic evaluation episodes. Not part of the test suite; docs/rltools.md says how to
# build RLtools (outside this repository, with RL_TOOLS_RL_ZOO_BENCHMARK) and records results.
#   RLTOOLS_BUILD_OPENBLAS=DIR RLTOOLS_BUILD_PLAIN=DIR RLRUN=BIN scripts/bench/rltools.sh [sac td3 ppo]
#   REPS=3 (runs of each variant, seeds 1..REPS)   OUT=FILE (also write the table there)
# RLTOOLS_BUILD_*: RLtools CMake build directories (either may be left unset to skip it) holding
# src/rl/zoo/rl_zoo_pendulum_v1_{sac,td3,ppo}. RLRUN: the rlrun binary (default build/rlrun).
# Per algorithm and repetition the variants run one after another, interleaved A B A B:
# RLtools+OpenBLAS, rlrun --threads 1, RLtools plain, rlrun --threads 2. RLtools runs with one
# thread (OMP_NUM_THREADS=OPENBLAS_NUM_THREADS=1); its zoo binary trains, then prints the mean
# return of 100 episodes. rlrun trains, then `rlrun eval --episodes 100 --seed 1000` scores the
# model. Wall time is the training process's (rlrun's evaluation is not counted; RLtools' is,
# and is also shown apart: "RLtools' own time" is the loop time it prints, evaluation excluded).
# The two returns come from different start states, which move a 100-episode mean by ~10 points
# (docs/rltools.md, "The return on the same start states"). So each seed's RLtools policy (the
# checkpoint.h its benchmark build writes) and rlrun's single-thread model are also scored by
# scripts/bench/rltools_cross_eval.py on RLtools' own 100 start states and on 10 000 common ones
# (needs numpy and rlrun's Python package: PYTHON, default /usr/bin/python3, with
# RLRUN_PYTHONPATH, default build/python; skipped with a note when either is missing).
# Run it on a quiet machine: the variants share the cores with nothing else.
# OpenBLAS picks its kernels by CPU model; one older than the CPU (Debian 12's 0.3.21 on a Zen 4
# or Zen 5) falls back to its AVX2 "Haswell" kernels on an AVX-512 CPU. OPENBLAS_CORETYPE (e.g.
# SkylakeX for its AVX-512 kernels) is passed through to RLtools and named in the table.
set -euo pipefail
cd "$(dirname "$0")/../.."
algos=("$@")
((${#algos[@]})) || algos=(sac td3 ppo)
reps=${REPS:-3}
rlrun=${RLRUN:-build/rlrun}
episodes=100  # RLtools' zoo evaluates 100 episodes (src/rl/zoo/zoo.cpp, NUM_EPISODES)
[[ -x "$rlrun" ]] || { echo "bench_rltools: no rlrun binary at '$rlrun' (set RLRUN)" >&2; exit 2; }
declare -A rltools_dirs=()
[[ -n "${RLTOOLS_BUILD_OPENBLAS:-}" ]] && rltools_dirs[openblas]=$RLTOOLS_BUILD_OPENBLAS
[[ -n "${RLTOOLS_BUILD_PLAIN:-}" ]] && rltools_dirs[plain]=$RLTOOLS_BUILD_PLAIN
((${#rltools_dirs[@]})) ||
  { echo "bench_rltools: set RLTOOLS_BUILD_OPENBLAS and/or RLTOOLS_BUILD_PLAIN (docs/rltools.md)" >&2; exit 2; }
for algo in "${algos[@]}"; do
  [[ -f configs/rltools/pendulum_$algo.yaml ]] || { echo "bench_rltools: unknown algorithm '$algo'" >&2; exit 2; }
  for kind in "${!rltools_dirs[@]}"; do
    bin=${rltools_dirs[$kind]}/src/rl/zoo/rl_zoo_pendulum_v1_$algo
    [[ -x "$bin" ]] || { echo "bench_rltools: no RLtools binary $bin" >&2; exit 2; }
  done
done
python=${PYTHON:-/usr/bin/python3}
rlrun_pythonpath=${RLRUN_PYTHONPATH:-build/python}
cross_eval=1
PYTHONPATH=$rlrun_pythonpath "$python" -c 'import numpy, rlrun' 2>/dev/null || {
  cross_eval=0
  echo "bench_rltools: no numpy or rlrun Python package for $python (PYTHONPATH=$rlrun_pythonpath):" \
       "the same-start-state returns are skipped (docs/python.md)" >&2
}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", b - a }'; }

# RLtools zoo run: writes "wall own_time return" to $out/<algo>.rltools-<kind>.<seed>.
run_rltools() {
  local algo=$1 kind=$2 seed=$3 dir start end log
  dir=$out/rltools-$kind-$algo-$seed
  log=$dir/stdout.txt
  mkdir -p "$dir"
  start=$(now)
  (cd "$dir" && OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 \
     "${rltools_dirs[$kind]}/src/rl/zoo/rl_zoo_pendulum_v1_$algo" -s "$seed" >"$log" 2>&1)
  end=$(now)
  if ! grep -q 'Mean return:' "$log"; then
    echo "bench_rltools: $kind $algo printed no 'Mean return:' (built without" \
         "-DRL_TOOLS_RL_ZOO_BENCHMARK? docs/rltools.md); its output:" >&2
    tail -5 "$log" >&2
    exit 1
  fi
  awk -v wall="$(elapsed "$start" "$end")" '
    /^Time: / { t = $2; sub(/s$/, "", t) }
    /Mean return:/ { for (i = 1; i <= NF; ++i) if ($i == "return:") r = $(i + 1) }
    END { printf "%.2f %s %s\n", wall, (t == "" ? "-" : t), r }' "$log" \
    >"$out/$algo.rltools-$kind.$seed"
  find "$dir" -name checkpoint.h -print -quit >"$out/$algo.checkpoint-$kind.$seed"
}

# Both policies of a seed on the same start states: writes "rltools_own rlrun_own
# rltools_common rlrun_common" (mean returns) to $out/<algo>.cross.<seed>.
run_cross_eval() {
  local algo=$1 seed=$2 checkpoint
  ((cross_eval)) || return 0
  checkpoint=$(cat "$out/$algo.checkpoint-openblas.$seed" 2>/dev/null ||
               cat "$out/$algo.checkpoint-plain.$seed" 2>/dev/null || true)
  [[ -n "$checkpoint" ]] || { echo "bench_rltools: RLtools wrote no checkpoint.h for $algo seed $seed" >&2; return 0; }
  PYTHONPATH=$rlrun_pythonpath "$python" scripts/bench/rltools_cross_eval.py --checkpoint "$checkpoint" \
    --model "$out/rlrun-t1-$algo-$seed/rltools_pendulum_$algo/seed$seed/model.zip" \
    --rltools-seed "$seed" >"$out/cross-$algo-$seed.log" ||
    { echo "bench_rltools: rltools_cross_eval.py failed:" >&2; tail -5 "$out/cross-$algo-$seed.log" >&2; exit 1; }
  awk '$1 == "cross_eval" { v[$2] = $4 " " $5 }
       END { print v["rltools_states"], v["common_states"] }' "$out/cross-$algo-$seed.log" \
    >"$out/$algo.cross.$seed"
}

# rlrun run: writes "wall - return" to $out/<algo>.rlrun-t<threads>.<seed>.
run_rlrun() {
  local algo=$1 threads=$2 seed=$3 dir start end ret
  dir=$out/rlrun-t$threads-$algo-$seed
  start=$(now)
  "$rlrun" --threads "$threads" train "configs/rltools/pendulum_$algo.yaml" --seed "$seed" \
    --out "$dir" >"$out/rlrun-t$threads-$algo-$seed.log" 2>&1 ||
    { echo "bench_rltools: rlrun train failed:" >&2; tail -5 "$out/rlrun-t$threads-$algo-$seed.log" >&2; exit 1; }
  end=$(now)
  ret=$("$rlrun" --threads 1 eval --model "$dir/rltools_pendulum_$algo/seed$seed/model.zip" \
          --episodes "$episodes" --seed 1000 | sed -n 's/.*mean_reward = \([-0-9.e+]*\).*/\1/p')
  printf "%s - %s\n" "$(elapsed "$start" "$end")" "$ret" >"$out/$algo.rlrun-t$threads.$seed"
}

median() { sort -g | awk '{ v[NR] = $1 } END { if (NR == 0) print "-"; else if (NR % 2) print v[(NR + 1) / 2]; else printf "%.2f\n", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

for algo in "${algos[@]}"; do
  for ((seed = 1; seed <= reps; ++seed)); do
    # A B A B: RLtools and rlrun alternate, so a change in machine load hits both.
    if [[ -n "${rltools_dirs[openblas]:-}" ]]; then
      echo "$algo seed $seed: RLtools + OpenBLAS" >&2
      run_rltools "$algo" openblas "$seed"
    fi
    echo "$algo seed $seed: rlrun --threads 1" >&2
    run_rlrun "$algo" 1 "$seed"
    if [[ -n "${rltools_dirs[plain]:-}" ]]; then
      echo "$algo seed $seed: RLtools (no BLAS)" >&2
      run_rltools "$algo" plain "$seed"
    fi
    echo "$algo seed $seed: rlrun --threads 2" >&2
    run_rlrun "$algo" 2 "$seed"
    run_cross_eval "$algo" "$seed"
  done
done

table=$(
  echo "| algorithm | implementation | threads | wall s (median of $reps) | RLtools' own time s | return, $episodes episodes (median) | returns by seed |"
  echo "| --- | --- | --- | --- | --- | --- | --- |"
  for algo in "${algos[@]}"; do
    for variant in rltools-openblas rlrun-t1 rltools-plain rlrun-t2; do
      compgen -G "$out/$algo.$variant.*" >/dev/null || continue
      case $variant in
        rltools-openblas) name="RLtools + OpenBLAS"; threads=1 ;;
        rltools-plain) name="RLtools (no BLAS)"; threads=1 ;;
        rlrun-t1) name="rlrun"; threads=1 ;;
        rlrun-t2) name="rlrun"; threads=2 ;;
      esac
      mapfile -t files < <(ls -v "$out/$algo.$variant".*)
      wall=$(cat "${files[@]}" | awk '{ print $1 }' | median)
      own=$(cat "${files[@]}" | awk '$2 != "-" { print $2 }' | median)
      ret=$(cat "${files[@]}" | awk '{ print $3 }' | median)
      by_seed=$(for f in "${files[@]}"; do awk '{ printf "%.1f", $3 }' "$f"; echo; done | paste -sd ' ' -)
      echo "| ${algo^^} | $name | $threads | $wall | $own | $ret | $by_seed |"
    done
  done
)
# The same policies on the same start states (columns of $out/<algo>.cross.<seed>).
same_states=$(
  compgen -G "$out/*.cross.*" >/dev/null || exit 0
  echo "| algorithm | start states | RLtools (median) | rlrun (median) | RLtools by seed | rlrun by seed |"
  echo "| --- | --- | --- | --- | --- | --- |"
  for algo in "${algos[@]}"; do
    compgen -G "$out/$algo.cross.*" >/dev/null || continue
    mapfile -t files < <(ls -v "$out/$algo.cross".*)
    for set in "RLtools' own 100:1" "10 000 common:3"; do
      col=${set##*:}
      r=$(cat "${files[@]}" | awk -v c="$col" '{ print $c }')
      l=$(cat "${files[@]}" | awk -v c="$col" '{ print $(c + 1) }')
      echo "| ${algo^^} | ${set%:*} | $(median <<<"$r") | $(median <<<"$l") | $(paste -sd ' ' <<<"$r") | $(paste -sd ' ' <<<"$l") |"
    done
  done
)
[[ -z "$same_states" ]] || table+=$'\n\nThe same policies on the same start states, Gymnasium\'s Pendulum (scripts/bench/rltools_cross_eval.py). On its own 100 states RLtools\' SAC and TD3 score what it printed; its PPO ~1 point more, as Gymnasium charges the clamped torque and RLtools the unclamped one:\n\n'"$same_states"
header="Pendulum-v1, $(date -u +%Y-%m-%d), $(nproc) CPUs ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')), load before the last run: $(cut -d' ' -f1-3 /proc/loadavg), OpenBLAS kernels: ${OPENBLAS_CORETYPE:-chosen by OpenBLAS}"
printf '%s\n\n%s\n' "$header" "$table"
[[ -z "${OUT:-}" ]] || printf '%s\n\n%s\n' "$header" "$table" >"$OUT"
