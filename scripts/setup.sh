#!/usr/bin/env bash
# Installs every Debian 12 package rlrun uses (DESIGN.md §2) and builds into build/.
# Idempotent: packages already present are not reinstalled, the build is incremental.
#   scripts/setup.sh            # install + build (Release)
#   RLRUN_SKIP_INSTALL=1 ...    # build only
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  cmake ninja-build g++ pkg-config          # toolchain
  libeigen3-dev                             # networks (nn/)
  libyaml-cpp-dev                           # experiment files
  libcli11-dev                              # command line
  nlohmann-json3-dev                        # meta.json in model files
  libspdlog-dev libfmt-dev                  # logging
  catch2                                    # tests (v2.13)
  libzip-dev zip unzip                      # model files are zips
  zlib1g-dev                                # gzip SUMO inputs checked (sumo_xml_guard); tests' hostile zips
  libbullet-dev                             # 3D grasp task
  libbox2d-dev                              # LunarLander, BipedalWalker (Gymnasium's Box2D tasks)
  libpugixml-dev                            # SUMO network files read before SUMO runs (traffic_network)
  sumo sumo-tools                           # traffic task (SUMO + TraCI)
  libcairo2-dev fonts-dejavu-core ffmpeg    # rendering (frames, overlay text) and video
  python3-numpy python3-pandas              # tests: read our files with the tools SB3 users use
  python3-protobuf                          # tests: decode TensorBoard event files independently
  python3-dev pybind11-dev python3-venv     # the `rlrun` Python package; Python envs (docs/python.md)
  python3-onnx                              # tests: the ONNX checker validates exported graphs
  python3-optuna                            # tests: Optuna loads and writes the studies rlrun tune keeps
  python3-sklearn python3-matplotlib        # tests: Optuna's importance and plot functions on them
)

if [[ -z "${RLRUN_SKIP_INSTALL:-}" ]]; then
  scripts/install_packages.sh "${PACKAGES[@]}"
fi

# SUMO's tools look for their data here (DESIGN.md §2).
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}

# Tests run exported policies in a real ONNX Runtime: the npm package onnxruntime-node (its CPU
# build ships inside the package; --ignore-scripts skips its optional CUDA download), installed
# into build/onnxruntime. Node.js and npm come from Debian when the machine has none.
ONNXRUNTIME_NODE_VERSION=1.20.1
if [[ -z "${RLRUN_SKIP_INSTALL:-}" ]]; then
  command -v npm >/dev/null || scripts/install_packages.sh nodejs npm
  if [[ ! -f build/onnxruntime/node_modules/onnxruntime-node/package.json ]] ||
     ! grep -q "\"version\": \"$ONNXRUNTIME_NODE_VERSION\"" build/onnxruntime/node_modules/onnxruntime-node/package.json; then
    mkdir -p build/onnxruntime
    npm install --prefix build/onnxruntime --ignore-scripts --no-audit --no-fund --silent \
      "onnxruntime-node@$ONNXRUNTIME_NODE_VERSION" >/dev/null
    echo "setup: onnxruntime-node $ONNXRUNTIME_NODE_VERSION in build/onnxruntime (tests)"
  fi
fi

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --parallel "$(nproc)"
echo "setup: built build/rlrun"

# The Python package (docs/python.md): build/python/rlrun is a ready package; a .pth file in
# Debian python3's site directory (the user's own when not root) puts build/python on its path,
# so `python3 -c "import rlrun"` works from anywhere. RLRUN_SITE_DIR picks another directory.
# The wheel for virtualenvs goes to build/python/dist/.
PYTHON=/usr/bin/python3
if [[ -x $PYTHON && -d build/python/rlrun ]]; then
  if [[ -n "${RLRUN_SITE_DIR:-}" ]]; then
    site=$RLRUN_SITE_DIR
  elif [[ $(id -u) -eq 0 ]]; then
    site=$($PYTHON -c 'import site; print(site.getsitepackages()[0])')
  else
    site=$($PYTHON -c 'import site; print(site.getusersitepackages())')
  fi
  mkdir -p "$site"
  echo "$(pwd)/build/python" > "$site/rlrun.pth"
  echo "setup: $site/rlrun.pth -> $(pwd)/build/python (import rlrun)"
  cmake --build build --target rlrun_wheel >/dev/null
  echo "setup: wheel in build/python/dist/ (VENV/bin/pip install --no-index build/python/dist/rlrun-*.whl)"
fi
