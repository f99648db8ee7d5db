#!/usr/bin/env bash
# A build without the optional components (docs/install.md, "Optional components"): configures
# BUILD_DIR (default build-minimal/) with RLRUN_WITH_SUMO, _BULLET, _BOX2D and _PYTHON off,
# builds the programs, and checks as a user would that
#   * nothing of SUMO, Bullet, Box2D or pugixml is linked, and no SUMO companion is built;
#   * PPO trains on CartPole, its model file evaluates, `rlrun list` works;
#   * a config that needs a component left out fails while it is read, at its env.id, naming
#     the CMake option and the Debian package, before any run directory is made.
# The library is compiled in batches, as scripts/setup.sh configures it (docs/install.md,
# "Compiling in batches"). scripts/test.sh runs it after ctest (a second build: about 8 minutes on 2
# cores without a compiler cache, less with ccache).
#   scripts/tests/test_minimal_build.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build-minimal}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
log=$work/log

fail() {
  echo "test_minimal_build: FAILED: $*" >&2
  [[ -f $log ]] && tail -20 "$log" >&2
  exit 1
}
run() { "$@" >"$log" 2>&1 || fail "$*"; }
expect_in_log() { grep -qF -- "$1" "$log" || fail "no '$1' in the output of the last command"; }

SECONDS=0
launcher=()
if [[ -n "${CMAKE_CXX_COMPILER_LAUNCHER:-}" ]]; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER="$CMAKE_CXX_COMPILER_LAUNCHER")
elif command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
run cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" -DRLRUN_UNITY_BUILD=ON \
  -DRLRUN_WITH_SUMO=OFF -DRLRUN_WITH_BULLET=OFF -DRLRUN_WITH_BOX2D=OFF -DRLRUN_WITH_PYTHON=OFF
expect_in_log "tests, benchmarks and fuzz targets: not built"
run cmake --build "$build" --target rlrun_programs
echo "test_minimal_build: built in ${SECONDS} s"
rlrun=$build/rlrun

# Nothing of the components left out is linked or built.
run ldd "$rlrun"
if grep -Ei "sumo|traci|bullet|box2d|pugixml" "$log"; then fail "rlrun links a component left out"; fi
for f in rlrun-sumo-worker librlrun_libsumo.so python/rlrun; do
  [[ ! -e $build/$f ]] || fail "$build/$f was built"
done

# The main job: PPO on CartPole (shortened), then its model evaluated.
run "$rlrun" train configs/cartpole_ppo.yaml --timesteps 8192 --out "$work/runs"
model=$(find "$work/runs" -name model.zip | head -1)
[[ -n $model ]] || fail "no model.zip under $work/runs"
run "$rlrun" eval --model "$model" --episodes 3
expect_in_log "mean_reward"
run "$rlrun" list
expect_in_log "CartPole-v1"
expect_in_log "TrafficNetwork-v0"
expect_in_log "(not built: -DRLRUN_WITH_SUMO=ON"
run "$rlrun" list LunarLander-v3
expect_in_log "-DRLRUN_WITH_BOX2D=ON"

# A config that needs a component left out: refused at its env.id, nothing made.
refused() {  # refused CONFIG OPTION PACKAGE [train options...]
  local config=$1 option=$2 package=$3
  shift 3
  if "$rlrun" train "$config" --out "$work/refused" "$@" >"$log" 2>&1; then
    fail "train $config ran without $option"
  fi
  expect_in_log "$config:"
  expect_in_log "env.id"
  expect_in_log "is not built into this rlrun"
  expect_in_log "-D$option=ON"
  expect_in_log "$package"
  [[ ! -e $work/refused ]] || fail "train $config made $work/refused"
}
refused configs/traffic_network_dqn.yaml RLRUN_WITH_SUMO sumo
refused configs/traffic_dqn.yaml RLRUN_WITH_SUMO sumo
refused configs/grasp_sac.yaml RLRUN_WITH_BULLET libbullet-dev
refused configs/lunarlander_dqn.yaml RLRUN_WITH_BOX2D libbox2d-dev
sed 's/id: CartPole-v1/id: "gymnasium:CartPole-v1"/' configs/cartpole_ppo.yaml >"$work/gymnasium_cartpole.yaml"
refused "$work/gymnasium_cartpole.yaml" RLRUN_WITH_PYTHON python3
echo "test_minimal_build: passed in ${SECONDS} s"
