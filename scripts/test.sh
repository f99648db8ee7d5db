#!/usr/bin/env bash
# Sets up (packages + the programs) if needed, builds the tests, runs them with ctest, then
# checks a second build without the optional components (scripts/tests/test_minimal_build.sh).
# Tests tagged [.slow] are hidden from this run; run them with
#   build/tests/rlrun_tests "[.slow]"
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --build build --parallel "$(nproc)"     # the tests, benchmarks and fuzz smoke targets too
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}
ctest --test-dir build --output-on-failure --parallel "$(nproc)" --timeout 900
scripts/tests/test_minimal_build.sh    # rlrun built without SUMO, Bullet, Box2D, Python (docs/install.md)
