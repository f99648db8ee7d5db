#!/usr/bin/env bash
# An installed rlrun runs on its own, wherever its prefix is moved: installs BUILD into a
# temporary prefix (`cmake --install`, nothing else copied), moves the prefix to another
# directory, and from an unrelated working directory trains CartPole from the installed
# configs, builds the grasp task from its shipped scenario, runs the traffic env on SUMO's
# shipped network (when sumo is installed; both backends) and checks that no path of the
# checkout is in the installed files, that a binary without its data says what to do, and
# that RLRUN_DATA_DIR points it at data elsewhere; then builds examples/embed_policy against the
# installed CMake package (rlrun::policy) and compares its actions with `rlrun eval`'s.
#   scripts/tests/test_install.sh [BUILD_DIR]       (ctest runs it as `install_relocatable`)
set -euo pipefail
source_dir=$(cd "$(dirname "$0")/../.." && pwd -P)
build=$(cd "${1:-$source_dir/build}" && pwd -P)
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}
unset RLRUN_DATA_DIR RLRUN_LIBSUMO_MODULE
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
log=$work/log

fail() {
  echo "test_install: FAILED: $*" >&2
  [[ -f $log ]] && tail -20 "$log" >&2
  exit 1
}
run() {  # runs a command, its output in $log; fails the test when it fails
  "$@" >"$log" 2>&1 || fail "$*"
}
expect_in_log() { grep -qF -- "$1" "$log" || fail "no '$1' in the output of the last command"; }

# 1. Install, then move the prefix: every path inside must be relative to the prefix.
run cmake --install "$build" --prefix "$work/first/prefix"
mkdir -p "$work/elsewhere"
mv "$work/first/prefix" "$work/elsewhere/rlrun"
rmdir "$work/first"
prefix=$work/elsewhere/rlrun
rlrun=$prefix/bin/rlrun
data=$prefix/share/rlrun
for file in bin/rlrun include/rlrun/plugin.hpp lib/cmake/rlrun/rlrunConfig.cmake \
            share/rlrun/configs/cartpole_ppo.yaml share/rlrun/configs/zoo/cartpole_ppo.yaml \
            share/rlrun/configs/sweeps/cartpole_ppo_lr.yaml share/rlrun/scenarios/grasp/lift.yaml \
            share/rlrun/scenarios/single_intersection.yaml \
            share/rlrun/sumo_data/single_intersection/single.sumocfg \
            share/rlrun/sumo_data/single_intersection/single.net.xml; do
  [[ -f $prefix/$file ]] || fail "the install has no $file"
done
[[ -n $(find "$prefix" -name librlrun_libsumo.so) ]] || fail "the install has no librlrun_libsumo.so"
worker=$(find "$prefix" -name rlrun-sumo-worker)
[[ -n $worker ]] || fail "the install has no rlrun-sumo-worker"
# No path of the checkout or the build tree in any installed binary (data paths, __FILE__).
for binary in "$rlrun" "$worker" $(find "$prefix" -name '*.so'); do
  for dir in "$source_dir" "$build"; do
    if grep -qaF "$dir" "$binary"; then
      fail "$binary contains '$dir': $(grep -aoF "$dir" "$binary" | head -3 | tr '\n' ' ')"
    fi
  done
done

# 2. From a directory that is neither the checkout nor the prefix.
mkdir "$work/cwd"
cd "$work/cwd"
run "$rlrun" --threads 1 train "$data/configs/cartpole_ppo.yaml" --timesteps 2000 --out "$work/runs"
[[ -f $work/runs/cartpole_ppo/seed1/model.zip ]] || fail "train wrote no model.zip"
run "$rlrun" eval --model "$work/runs/cartpole_ppo/seed1/model.zip" --episodes 2
expect_in_log "mean_reward"
if grep -rqaF "$source_dir" "$work/runs"; then
  fail "the run directory names the checkout: $(grep -rlaF "$source_dir" "$work/runs" | head -3)"
fi

# The grasp task reads scenarios/grasp/lift.yaml (the default) or a shipped scenario named
# relative to the data directory.
run "$rlrun" check-env GripperLift-v0 --steps 20 --episodes 1
expect_in_log "check_env: passed"
run "$rlrun" check-env GripperLift-v0 --steps 20 --episodes 1 --set scenario=scenarios/grasp/lift_easy.yaml
expect_in_log "check_env: passed"

# The traffic env runs SUMO on sumo_data/single_intersection, over TraCI and in-process
# (lib/librlrun_libsumo.so, found from bin/).
if command -v sumo >/dev/null; then
  run "$rlrun" check-env TrafficSignal-v0 --steps 20 --episodes 1 --set num_seconds=600
  expect_in_log "check_env: passed"
  run "$rlrun" check-env TrafficSignal-v0 --steps 20 --episodes 1 --set num_seconds=600 --set backend=libsumo
  expect_in_log "check_env: passed"
  # TrafficNetwork-v0: scenarios/grid4x4.yaml and its SUMO worker (lib/rlrun-sumo-worker),
  # SUMO inside the worker.
  run "$rlrun" check-env TrafficNetwork-v0 --steps 20 --episodes 1 --set num_seconds=300 --set backend=libsumo
  expect_in_log "check_env: passed"
else
  echo "test_install: sumo not installed: traffic env not checked"
fi

# 3. The binary without its data: a clear error naming the places and RLRUN_DATA_DIR, then
# RLRUN_DATA_DIR makes it work.
mkdir -p "$work/lonely/bin"
cp "$rlrun" "$work/lonely/bin/"
if "$work/lonely/bin/rlrun" check-env GripperLift-v0 --steps 20 --episodes 1 >"$log" 2>&1; then
  fail "a binary without its share/rlrun ran the grasp task"
fi
expect_in_log "$work/lonely/share/rlrun"
expect_in_log "RLRUN_DATA_DIR"
RLRUN_DATA_DIR=$data run "$work/lonely/bin/rlrun" check-env GripperLift-v0 --steps 20 --episodes 1
expect_in_log "check_env: passed"

# 4. rlrun::policy from the installed CMake package: examples/embed_policy builds out of tree
# against the moved prefix and acts as `rlrun eval` does on the observations of eval episodes
# (discrete CartPole actions equal, SAC Pendulum's within 1e-5).
[[ -f $prefix/include/rlrun/policy.hpp && -n $(find "$prefix" -name 'librlrun_policy.so*') ]] ||
  fail "the install has no rlrun::policy (include/rlrun/policy.hpp, librlrun_policy.so)"
run cmake -S "$source_dir/examples/embed_policy" -B "$work/embed" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix"
run cmake --build "$work/embed"
run "$rlrun" --threads 1 train "$data/configs/pendulum_sac.yaml" --timesteps 300 \
  --set algo.learning_starts=100 --out "$work/runs"
for model in cartpole_ppo pendulum_sac; do
  zip=$work/runs/$model/seed1/model.zip
  run "$rlrun" eval --model "$zip" --episodes 3 --seed 5 --trajectory "$work/$model.csv"
  run /usr/bin/python3 - "$work/$model.csv" "$work/$model.obs" <<'PY'
import csv, struct, sys
rows = list(csv.DictReader(open(sys.argv[1])))
obs = [k for k in rows[0] if k.startswith("obs_")]
with open(sys.argv[2], "wb") as out:
    for r in rows:
        out.write(struct.pack("<%df" % len(obs), *[float(r[k]) for k in obs]))
PY
  run "$work/embed/embed_policy" "$zip" "$work/$model.obs" "$work/$model.act"
  run /usr/bin/python3 - "$work/$model.csv" "$work/$model.act" <<'PY'
import csv, struct, sys
rows = list(csv.DictReader(open(sys.argv[1])))
act = [k for k in rows[0] if k.startswith("action_")]
data = open(sys.argv[2], "rb").read()
got = struct.unpack("<%df" % (len(data) // 4), data)
assert len(got) == len(rows) * len(act), (len(got), len(rows))
for i, r in enumerate(rows):
    for j, k in enumerate(act):
        want, have = float(r[k]), got[i * len(act) + j]
        assert abs(want - have) <= 1e-5 * max(1.0, abs(want)), (i, k, want, have)
print("embed_policy: %d actions as rlrun eval" % len(rows))
PY
  expect_in_log "as rlrun eval"
done

echo "test_install: passed (install in $prefix, moved; run from $work/cwd)"
