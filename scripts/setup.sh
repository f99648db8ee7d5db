#!/usr/bin/env bash
# Installs the Debian 12 packages rlrun uses and builds the programs into build/ (not the tests:
# scripts/test.sh builds those). Says what it will change on the system before it does it.
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
  libmujoco-dev libqhull-dev                # Gymnasium's MuJoCo tasks (MuJoCo 2.2.2; its CMake config names qhull's headers)
  libosmesa6-dev                            # MuJoCo's renderer on an offscreen context (record, headless)
  libpugixml-dev                            # SUMO network files read before SUMO runs (traffic_network)
  sumo sumo-tools                           # traffic task (SUMO + TraCI)
  libcairo2-dev fonts-dejavu-core ffmpeg    # rendering (frames, overlay text) and video
  python3-numpy python3-pandas              # tests: read our files with the tools SB3 users use
  python3-protobuf                          # tests: decode TensorBoard event files independently
  python3-dev pybind11-dev python3-venv     # the `rlrun` Python package; Python envs (docs/python.md)
  python3-onnx                              # tests: the ONNX checker validates exported graphs
  python3-optuna                            # tests: Optuna loads and writes the studies rlrun tune keeps
  python3-sklearn python3-matplotlib        # tests: Optuna's importance and plot functions on them
  clang-format-14                           # tests: the sources' layout (.clang-format)
)

# The Python package's .pth file (below): Debian python3's site directory, the user's own when
# not root; RLRUN_SITE_DIR picks another directory.
PYTHON=/usr/bin/python3
site_dir() {
  if [[ -n "${RLRUN_SITE_DIR:-}" ]]; then
    echo "$RLRUN_SITE_DIR"
  elif [[ $(id -u) -eq 0 ]]; then
    $PYTHON -c 'import site; print(site.getsitepackages()[0])'
  else
    $PYTHON -c 'import site; print(site.getusersitepackages())'
  fi
}

# What this script changes outside the checkout, said before it changes anything.
if [[ -z "${RLRUN_SKIP_INSTALL:-}" ]]; then
  missing=$(scripts/install_packages.sh --list-missing "${PACKAGES[@]}")
  command -v npm >/dev/null || missing="$missing nodejs npm"   # for ONNX Runtime in the tests
  [[ -n $missing ]] && echo "setup: will install Debian packages with apt-get: $missing"
fi
if [[ -x $PYTHON ]]; then
  echo "setup: will write $(site_dir)/rlrun.pth (one line: $(pwd)/build/python, so python3 can import rlrun)"
fi

if [[ -z "${RLRUN_SKIP_INSTALL:-}" ]]; then
  scripts/install_packages.sh "${PACKAGES[@]}"
fi

# SUMO's tools look for their data here.
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

# Every optional component (docs/install.md): the packages above bring them all, and a build
# that silently lost one would also lose the tests that need it. The library is compiled in
# batches (RLRUN_UNITY_BUILD, docs/install.md "Compiling in batches"): a build from scratch takes
# about half the CPU time. RLRUN_UNITY_BUILD=OFF scripts/setup.sh for file-by-file rebuilds.
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DRLRUN_WITH_SUMO=ON -DRLRUN_WITH_BULLET=ON \
  -DRLRUN_WITH_BOX2D=ON -DRLRUN_WITH_PYTHON=ON -DRLRUN_UNITY_BUILD="${RLRUN_UNITY_BUILD:-ON}" >/dev/null
cmake --build build --parallel "$(nproc)" --target rlrun_programs
echo "setup: built build/rlrun"

# The Python package (docs/python.md): build/python/rlrun is a ready package; the .pth file
# puts build/python on python3's path, so `python3 -c "import rlrun"` works from anywhere.
# The wheel for virtualenvs goes to build/python/dist/.
if [[ -x $PYTHON && -d build/python/rlrun ]]; then
  site=$(site_dir)
  mkdir -p "$site"
  echo "$(pwd)/build/python" > "$site/rlrun.pth"
  echo "setup: $site/rlrun.pth -> $(pwd)/build/python (import rlrun)"
  cmake --build build --target rlrun_wheel >/dev/null
  echo "setup: wheel in build/python/dist/ (VENV/bin/pip install --no-index build/python/dist/rlrun-*.whl)"
fi
