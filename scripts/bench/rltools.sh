#!/usr/bin/env bash
# RLtools' zoo beside rlrun running the same hyperparameters (configs/rltools/): wall time to
# RLtools' step budget, env steps per second and the final return over 100 deterministic
# evaluation episodes. Experiments: sac td3 ppo (Pendulum-v1) and ant_ppo ant_td3 (Ant-v4).
# Not part of the test suite; docs/rltools.md says how to build RLtools (outside this
# repository, with RL_TOOLS_RL_ZOO_BENCHMARK) and records results.
#   RLTOOLS_BUILD_OPENBLAS=DIR RLTOOLS_BUILD_PLAIN=DIR RLRUN=BIN scripts/bench/rltools.sh [EXPERIMENT...]
#   EXPERIMENT: sac td3 ppo (the default) ant_ppo ant_td3
#   REPS=3 (runs of each variant, seeds 1..REPS)   OUT=FILE (also write the table there)
#   CPUS=0,1 (the cores the runs are pinned to: one-core runs use the first)
#   KEEP=DIR (keep every run's directory there: RLtools' checkpoint.h, rlrun's model.zip, logs)
#   TABLES_ONLY=1 (with KEEP: run nothing, remake the tables from that directory's results)
#   ANT_TD3_STEP_LIMIT=N (ant_td3 only: a shorter run, for speed on a budget; RLtools built from a
#     tree whose src/rl/zoo/ant-v4/td3.h has STEP_LIMIT = N, which its replay buffer's capacity
#     follows; rlrun then trains N + 1 steps with buffer_size N. The bench checks that RLtools
#     printed the same limit. docs/rltools.md, "TD3 on a shorter budget")
# RLTOOLS_BUILD_*: RLtools CMake build directories (either may be left unset to skip it) holding
# src/rl/zoo/rl_zoo_pendulum_v1_{sac,td3,ppo} and, for the Ant experiments (RLtools configured
# with RL_TOOLS_RL_ENVIRONMENTS_ENABLE_MUJOCO), rl_zoo_ant_v4_{ppo,td3}. RLRUN: the rlrun binary
# (default build/rlrun; built with MuJoCo for the Ant experiments).
# Per experiment and repetition the variants run one after another, interleaved A B A B:
# RLtools+OpenBLAS on one core, rlrun --threads 1, RLtools without BLAS on one core, rlrun
# --threads 2, and for Ant RLtools+OpenBLAS on two cores. Every run is pinned with taskset (one
# core: the first of CPUS; two: the first two). RLtools' Pendulum zoo is single-threaded; its Ant
# zoo steps the envs of its PPO in 16 threads (zoo.cpp's ExecutionHints), which then share the
# cores it is given; OMP_NUM_THREADS = OPENBLAS_NUM_THREADS = its number of cores. Its zoo binary
# trains, then prints the mean return of 100 episodes. rlrun trains, then `rlrun eval --episodes
# 100 --seed 1000` scores the model. Wall time is the training process's (rlrun's evaluation is
# not counted; RLtools' is, and is also shown apart: "RLtools' own time" is the loop time it
# prints, evaluation excluded: 100 Ant episodes are up to 100 000 env steps). Env steps: what
# each implementation steps (RLtools' PPO adds one rollout for its observation statistics);
# env steps/s divides them by RLtools' own time, or by rlrun's wall time.
# The two returns come from different start states, which move a 100-episode mean by ~10 points
# on Pendulum (docs/rltools.md, "The return on the same start states"). So each Pendulum seed's
# RLtools policy (the checkpoint.h its benchmark build writes) and rlrun's single-thread model
# are also scored by scripts/bench/rltools_cross_eval.py on RLtools' own 100 start states and on
# 10 000 common ones, each Ant seed's by scripts/bench/rltools_cross_eval_ant.py on RLtools' own
# 100 and 100 common ones (needs numpy and rlrun's Python package: PYTHON, default
# /usr/bin/python3, with RLRUN_PYTHONPATH, default build/python; skipped with a note when either
# is missing).
# Run it on a quiet machine: the variants share the cores with nothing else.
# OpenBLAS picks its kernels by CPU model; one older than the CPU (Debian 12's 0.3.21 on a Zen 4
# or Zen 5) falls back to its AVX2 "Haswell" kernels on an AVX-512 CPU. OPENBLAS_CORETYPE (e.g.
# SkylakeX for its AVX-512 kernels) is passed through to RLtools and named in the table.
set -euo pipefail
cd "$(dirname "$0")/../.."
experiments=("$@")
((${#experiments[@]})) || experiments=(sac td3 ppo)
reps=${REPS:-3}
rlrun=${RLRUN:-build/rlrun}
episodes=100  # RLtools' zoo evaluates 100 episodes (src/rl/zoo/zoo.cpp, NUM_EPISODES)
IFS=, read -r -a cpus <<<"${CPUS:-0,1}"
((${#cpus[@]} >= 2)) || { echo "bench_rltools: CPUS must name two cores (e.g. 0,1)" >&2; exit 2; }
one_core=${cpus[0]}
two_cores=${cpus[0]},${cpus[1]}
command -v taskset >/dev/null || { echo "bench_rltools: needs taskset (Debian's util-linux)" >&2; exit 2; }
[[ -x "$rlrun" ]] || { echo "bench_rltools: no rlrun binary at '$rlrun' (set RLRUN)" >&2; exit 2; }
declare -A rltools_dirs=()
[[ -n "${RLTOOLS_BUILD_OPENBLAS:-}" ]] && rltools_dirs[openblas]=$RLTOOLS_BUILD_OPENBLAS
[[ -n "${RLTOOLS_BUILD_PLAIN:-}" ]] && rltools_dirs[plain]=$RLTOOLS_BUILD_PLAIN
((${#rltools_dirs[@]})) ||
  { echo "bench_rltools: set RLTOOLS_BUILD_OPENBLAS and/or RLTOOLS_BUILD_PLAIN (docs/rltools.md)" >&2; exit 2; }

# An experiment's rlrun config, RLtools zoo target and the env steps RLtools takes beyond the
# config's budget (PPO: the rollout of the initial policy its observation statistics start from).
describe() {
  case $1 in
    sac | td3) config=configs/rltools/pendulum_$1.yaml target=rl_zoo_pendulum_v1_$1 extra=0 ;;
    ppo) config=configs/rltools/pendulum_ppo.yaml target=rl_zoo_pendulum_v1_ppo extra=8192 ;;
    ant_ppo) config=configs/rltools/ant_ppo.yaml target=rl_zoo_ant_v4_ppo extra=4096 ;;
    ant_td3) config=configs/rltools/ant_td3.yaml target=rl_zoo_ant_v4_td3 extra=0 ;;
    *) echo "bench_rltools: unknown experiment '$1' (sac td3 ppo ant_ppo ant_td3)" >&2; exit 2 ;;
  esac
  run_name=rltools_$(basename "$config" .yaml)
  budget=$(awk '$1 == "total_timesteps:" { print $2; exit }' "$config")
  rlrun_overrides=()
  rltools_limit=""  # the STEP_LIMIT RLtools must print ("" = not checked)
  if [[ $1 == ant_td3 && -n "${ANT_TD3_STEP_LIMIT:-}" ]]; then
    # RLtools' TD3 loop tests `step > STEP_LIMIT` after its increment: STEP_LIMIT + 1 env steps
    # (as the config's 1000001); its buffer holds STEP_LIMIT transitions (zoo td3.h).
    budget=$((ANT_TD3_STEP_LIMIT + 1)) rltools_limit=$ANT_TD3_STEP_LIMIT
    rlrun_overrides=(--timesteps "$budget" --set "algo.buffer_size=$ANT_TD3_STEP_LIMIT")
  fi
}
[[ -z "${ANT_TD3_STEP_LIMIT:-}" || "$ANT_TD3_STEP_LIMIT" =~ ^[1-9][0-9]*$ ]] ||
  { echo "bench_rltools: ANT_TD3_STEP_LIMIT must be a positive integer" >&2; exit 2; }
is_pendulum() { [[ $1 == sac || $1 == td3 || $1 == ppo ]]; }
for experiment in "${experiments[@]}"; do
  describe "$experiment"
  for kind in "${!rltools_dirs[@]}"; do
    bin=${rltools_dirs[$kind]}/src/rl/zoo/$target
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
[[ -z "${TABLES_ONLY:-}" || -n "${KEEP:-}" ]] ||
  { echo "bench_rltools: TABLES_ONLY needs KEEP (the directory of an earlier run)" >&2; exit 2; }
if [[ -n "${KEEP:-}" ]]; then
  out=$KEEP
  mkdir -p "$out"
else
  out=$(mktemp -d)
  trap 'rm -rf "$out"' EXIT
fi
now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", b - a }'; }

# TD3 Ant: milliseconds per training step (one env step, one critic update, the actor every
# second) from step 30 000 on, when both act with the policy and train. The wall times alone
# do not compare equal work: RLtools trains from step 100, rlrun from learning_starts 20 000
# (configs/rltools/ant_td3.yaml), 2 % of a 1 M run and 20 % of a 100 000 one.
# RLtools: its "Loop step: N, ... (elapsed: E s)" lines; rlrun: progress.csv's
# time/total_timesteps and time/time_elapsed.
td3_step_ms_rltools() {
  awk '/^Loop step: / { n = $3; sub(/,$/, "", n); n += 0; e = $(NF - 1)
                        if (n >= 30000) { if (n0 == "") { n0 = n; e0 = e } n1 = n; e1 = e } }
       END { if (n1 > n0) printf "%.3f\n", 1000 * (e1 - e0) / (n1 - n0); else print "-" }' "$1"
}
td3_step_ms_rlrun() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
           { n = $c["time/total_timesteps"] + 0; e = $c["time/time_elapsed"]
             if (n >= 30000) { if (n0 == "") { n0 = n; e0 = e } n1 = n; e1 = e } }
           END { if (n1 > n0) printf "%.3f\n", 1000 * (e1 - e0) / (n1 - n0); else print "-" }' "$1"
}

# RLtools zoo run on `cores` (1 or 2): writes "wall own_time return env_steps" to
# $out/<experiment>.rltools-<kind>-c<cores>.<seed>.
run_rltools() {
  local experiment=$1 kind=$2 cores=$3 seed=$4 dir start end log cpu_list status
  describe "$experiment"
  dir=$out/rltools-$kind-c$cores-$experiment-$seed
  log=$dir/stdout.txt
  cpu_list=$([[ $cores == 1 ]] && echo "$one_core" || echo "$two_cores")
  mkdir -p "$dir"
  start=$(now)
  status=0
  (cd "$dir" && OMP_NUM_THREADS=$cores OPENBLAS_NUM_THREADS=$cores \
     taskset -c "$cpu_list" "${rltools_dirs[$kind]}/src/rl/zoo/$target" -s "$seed" >"$log" 2>&1) ||
    status=$?
  end=$(now)
  if ! grep -q 'Mean return:' "$log"; then
    echo "bench_rltools: $kind $experiment printed no 'Mean return:' (built without" \
         "-DRL_TOOLS_RL_ZOO_BENCHMARK? docs/rltools.md); its output:" >&2
    tail -5 "$log" >&2
    exit 1
  fi
  if [[ -n "$rltools_limit" ]] && ! grep -q "Step: [0-9]*/$rltools_limit " "$log"; then
    echo "bench_rltools: $kind $experiment was not built with STEP_LIMIT $rltools_limit" \
         "(ANT_TD3_STEP_LIMIT); it printed: $(grep -m1 'Mean return:' "$log")" >&2
    exit 1
  fi
  # RLtools @9acdf5c8's Ant PPO zoo aborts in free() after writing its final checkpoint.h, its
  # result already printed (docs/rltools.md): kept, with the exit status shown.
  ((status == 0)) || echo "bench_rltools: $kind $experiment seed $seed exited with status $status" \
    "after printing its result ($(tail -1 "$log"))" >&2
  awk -v wall="$(elapsed "$start" "$end")" -v steps="$((budget + extra))" '
    /^Time: / { t = $2; sub(/s$/, "", t) }
    /Mean return:/ { for (i = 1; i <= NF; ++i) if ($i == "return:") r = $(i + 1) }
    END { printf "%.2f %s %s %d\n", wall, (t == "" ? "-" : t), r, steps }' "$log" \
    >"$out/$experiment.rltools-$kind-c$cores.$seed"
  find "$dir" -name checkpoint.h -print -quit >"$out/$experiment.checkpoint-$kind.$seed"
  [[ $experiment != ant_td3 ]] || td3_step_ms_rltools "$log" >"$out/$experiment.step-ms-rltools-$kind-c$cores.$seed"
}

# Both policies of a seed on the same start states: writes "rltools_own rlrun_own rltools_common
# rlrun_common" (mean returns; "- -" for a set not scored) to $out/<experiment>.cross.<seed>.
# Pendulum: RLtools' own 100 start states and 10 000 common ones (rltools_cross_eval.py); Ant:
# RLtools' own 100 and 100 common ones (rltools_cross_eval_ant.py).
run_cross_eval() {
  local experiment=$1 seed=$2 checkpoint tool args
  ((cross_eval)) || return 0
  case $experiment in
    sac | td3 | ppo) tool=rltools_cross_eval.py args=(--rltools-seed "$seed") ;;
    ant_ppo | ant_td3) tool=rltools_cross_eval_ant.py args=(--rltools-seed "$seed") ;;
    *) return 0 ;;
  esac
  describe "$experiment"
  checkpoint=$(cat "$out/$experiment.checkpoint-openblas.$seed" 2>/dev/null ||
               cat "$out/$experiment.checkpoint-plain.$seed" 2>/dev/null || true)
  [[ -n "$checkpoint" ]] || { echo "bench_rltools: RLtools wrote no checkpoint.h for $experiment seed $seed" >&2; return 0; }
  PYTHONPATH=$rlrun_pythonpath "$python" "scripts/bench/$tool" --checkpoint "$checkpoint" \
    --model "$out/rlrun-t1-$experiment-$seed/$run_name/seed$seed/model.zip" \
    "${args[@]}" >"$out/cross-$experiment-$seed.log" ||
    { echo "bench_rltools: $tool failed:" >&2; tail -5 "$out/cross-$experiment-$seed.log" >&2; exit 1; }
  awk '$1 == "cross_eval" { v[$2] = $4 " " $5 }
       END { print (v["rltools_states"] == "" ? "- -" : v["rltools_states"]), v["common_states"] }' \
    "$out/cross-$experiment-$seed.log" >"$out/$experiment.cross.$seed"
}

# rlrun run: writes "wall - return env_steps" to $out/<experiment>.rlrun-t<threads>.<seed>.
run_rlrun() {
  local experiment=$1 threads=$2 seed=$3 dir start end ret cpu_list
  describe "$experiment"
  dir=$out/rlrun-t$threads-$experiment-$seed
  cpu_list=$([[ $threads == 1 ]] && echo "$one_core" || echo "$two_cores")
  start=$(now)
  taskset -c "$cpu_list" "$rlrun" --threads "$threads" train "$config" --seed "$seed" \
    "${rlrun_overrides[@]}" --out "$dir" >"$out/rlrun-t$threads-$experiment-$seed.log" 2>&1 ||
    { echo "bench_rltools: rlrun train failed:" >&2; tail -5 "$out/rlrun-t$threads-$experiment-$seed.log" >&2; exit 1; }
  end=$(now)
  ret=$("$rlrun" --threads 1 eval --model "$dir/$run_name/seed$seed/model.zip" \
          --episodes "$episodes" --seed 1000 | sed -n 's/.*mean_reward = \([-0-9.e+]*\).*/\1/p')
  printf "%s - %s %d\n" "$(elapsed "$start" "$end")" "$ret" "$budget" >"$out/$experiment.rlrun-t$threads.$seed"
  [[ $experiment != ant_td3 ]] ||
    td3_step_ms_rlrun "$dir/$run_name/seed$seed/progress.csv" >"$out/$experiment.step-ms-rlrun-t$threads.$seed"
}

# The variants with results $out/<prefix><variant>.<seed>, in the tables' order.
variants_with() {
  local variant
  for variant in rltools-openblas-c1 rlrun-t1 rltools-plain-c1 rlrun-t2 rltools-openblas-c2; do
    compgen -G "$out/$1$variant.*" >/dev/null && echo "$variant"
  done
  return 0
}
variant_name() {
  case $1 in
    rltools-openblas-c*) echo "RLtools + OpenBLAS" ;;
    rltools-plain-c*) echo "RLtools (no BLAS)" ;;
    rlrun-t*) echo "rlrun --threads ${1#rlrun-t}" ;;
  esac
}
median() { sort -g | awk '{ v[NR] = $1 } END { if (NR == 0) print "-"; else if (NR % 2) print v[(NR + 1) / 2]; else printf "%.2f\n", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

for experiment in "${experiments[@]}"; do
  [[ -z "${TABLES_ONLY:-}" ]] || break
  for ((seed = 1; seed <= reps; ++seed)); do
    # A B A B: RLtools and rlrun alternate, so a change in machine load hits both.
    if [[ -n "${rltools_dirs[openblas]:-}" ]]; then
      echo "$experiment seed $seed: RLtools + OpenBLAS, one core" >&2
      run_rltools "$experiment" openblas 1 "$seed"
    fi
    echo "$experiment seed $seed: rlrun --threads 1" >&2
    run_rlrun "$experiment" 1 "$seed"
    if [[ -n "${rltools_dirs[plain]:-}" ]]; then
      echo "$experiment seed $seed: RLtools (no BLAS), one core" >&2
      run_rltools "$experiment" plain 1 "$seed"
    fi
    echo "$experiment seed $seed: rlrun --threads 2" >&2
    run_rlrun "$experiment" 2 "$seed"
    if ! is_pendulum "$experiment" && [[ -n "${rltools_dirs[openblas]:-}" ]]; then
      echo "$experiment seed $seed: RLtools + OpenBLAS, two cores" >&2
      run_rltools "$experiment" openblas 2 "$seed"
    fi
    run_cross_eval "$experiment" "$seed"
  done
done

table=$(
  echo "| experiment | implementation | cores | env steps | wall s (median of $reps) | RLtools' own time s | env steps/s | return, $episodes episodes (median) | returns by seed |"
  echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"
  for experiment in "${experiments[@]}"; do
    for variant in $(variants_with "$experiment."); do
      name=$(variant_name "$variant")
      cores=${variant##*[ct]}
      mapfile -t files < <(ls -v "$out/$experiment.$variant".*)
      wall=$(cat "${files[@]}" | awk '{ print $1 }' | median)
      own=$(cat "${files[@]}" | awk '$2 != "-" { print $2 }' | median)
      ret=$(cat "${files[@]}" | awk '{ print $3 }' | median)
      steps=$(awk '{ print $4; exit }' "${files[0]}")
      rate=$(awk -v s="$steps" -v own="$own" -v wall="$wall" \
               'BEGIN { t = (own == "-" ? wall : own); printf "%.0f", s / t }')
      by_seed=$(for f in "${files[@]}"; do awk '{ printf "%.1f", $3 }' "$f"; echo; done | paste -sd ' ' -)
      echo "| $experiment | $name | $cores | $steps | $wall | $own | $rate | $ret | $by_seed |"
    done
  done
)
# TD3 Ant's time per training step (td3_step_ms_*), where the wall times do not compare equal work.
step_ms=$(
  compgen -G "$out/*.step-ms-*" >/dev/null || exit 0
  echo "| experiment | implementation | cores | ms per training step from step 30 000 (median) | by seed |"
  echo "| --- | --- | --- | --- | --- |"
  for experiment in "${experiments[@]}"; do
    for variant in $(variants_with "$experiment.step-ms-"); do
      values=$(cat $(ls -v "$out/$experiment.step-ms-$variant".*))
      echo "| $experiment | $(variant_name "$variant") | ${variant##*[ct]} | $(median <<<"$values") | $(paste -sd ' ' <<<"$values") |"
    done
  done
)
[[ -z "$step_ms" ]] || table+=$'\n\nTD3 per training step (one env step, one critic update, the actor every second), where both act with the policy and train; RLtools also trains during its 20 000 random steps, rlrun not (docs/rltools.md):\n\n'"$step_ms"
# The same Pendulum policies on the same start states (columns of $out/<experiment>.cross.<seed>).
same_states=$(
  compgen -G "$out/*.cross.*" >/dev/null || exit 0
  echo "| experiment | start states | RLtools (median) | rlrun (median) | RLtools by seed | rlrun by seed |"
  echo "| --- | --- | --- | --- | --- | --- |"
  for experiment in "${experiments[@]}"; do
    compgen -G "$out/$experiment.cross.*" >/dev/null || continue
    mapfile -t files < <(ls -v "$out/$experiment.cross".*)
    common=$(is_pendulum "$experiment" && echo "10 000 common" || echo "100 common")
    for set in "RLtools' own 100:1" "$common:3"; do
      col=${set##*:}
      r=$(cat "${files[@]}" | awk -v c="$col" '{ print $c }')
      l=$(cat "${files[@]}" | awk -v c="$col" '{ print $(c + 1) }')
      [[ $(sort -u <<<"$r") != "-" ]] || continue
      echo "| $experiment | ${set%:*} | $(median <<<"$r") | $(median <<<"$l") | $(paste -sd ' ' <<<"$r") | $(paste -sd ' ' <<<"$l") |"
    done
  done
)
[[ -z "$same_states" ]] || table+=$'\n\nThe same policies on the same start states, Gymnasium\'s Pendulum and rlrun\'s Ant-v4 (scripts/bench/rltools_cross_eval.py, rltools_cross_eval_ant.py). On its own 100 states RLtools\' Pendulum SAC and TD3 score what it printed; its PPO ~1 point more, as Gymnasium charges the clamped torque and RLtools the unclamped one; its Ant episodes are replayed on Gymnasium\'s rules (its first step differs, docs/rltools.md):\n\n'"$same_states"
header="RLtools' zoo beside rlrun, $(date -u +%Y-%m-%d), $(nproc) CPUs ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')), pinned to cores $two_cores, load before the last run: $(cut -d' ' -f1-3 /proc/loadavg), OpenBLAS kernels: ${OPENBLAS_CORETYPE:-chosen by OpenBLAS}"
printf '%s\n\n%s\n' "$header" "$table"
[[ -z "${OUT:-}" ]] || printf '%s\n\n%s\n' "$header" "$table" >"$OUT"
