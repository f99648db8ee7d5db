#!/usr/bin/env bash
# Builds rlrun, its tests and the fuzz targets with AddressSanitizer + UndefinedBehaviorSanitizer
# (cmake -DRLRUN_SANITIZE=ON, any UB fatal) into build-sanitize/ and runs the whole ctest suite
# under them: the test binary, the rlrun processes the CLI tests start, forked children and
# in-process SUMO (libsumo) and Bullet. Not part of .ci/run (slow); run it before a release or
# after touching code that parses files. Needs only what scripts/setup.sh installs (gcc's
# libasan/libubsan).
#   scripts/test_sanitize.sh [ctest options, e.g. -R cli]
# Every sanitizer report, from any process, is also written to build-sanitize/sanitizer-logs/;
# the script fails when that directory is not empty after the run, even if the test that
# started the process did not look at its exit code (86 for a sanitizer report).
# Suppressions (scripts/sanitize/*.supp) are for third-party libraries only, each justified.
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS=0
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRLRUN_SANITIZE=ON \
  ${CMAKE_CXX_COMPILER_LAUNCHER:+-DCMAKE_CXX_COMPILER_LAUNCHER=$CMAKE_CXX_COMPILER_LAUNCHER} >/dev/null
cmake --build build-sanitize
echo "sanitize: built in ${SECONDS} s"
# The ONNX export tests run onnxruntime-node, which scripts/setup.sh installs into build/.
if [ -d build/onnxruntime ] && [ ! -e build-sanitize/onnxruntime ]; then
  ln -s ../build/onnxruntime build-sanitize/onnxruntime
fi

LOGS=$PWD/build-sanitize/sanitizer-logs
rm -rf "$LOGS" && mkdir -p "$LOGS"
SUPP=$PWD/scripts/sanitize
common="exitcode=86:log_path=$LOGS/report:print_suppressions=0"
export ASAN_OPTIONS="$common:detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
export LSAN_OPTIONS="$common:suppressions=$SUPP/lsan.supp"
export UBSAN_OPTIONS="$common:print_stacktrace=1:halt_on_error=1:suppressions=$SUPP/ubsan.supp"
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}

test_start=$SECONDS
set +e
ctest --test-dir build-sanitize --parallel 2 --output-on-failure "$@"
status=$?
set -e
echo "sanitize: ctest exit $status in $((SECONDS - test_start)) s (total ${SECONDS} s)"
if compgen -G "$LOGS/report*" >/dev/null; then
  echo "sanitize: sanitizer reports:"
  for f in "$LOGS"/report*; do echo "== $f"; head -60 "$f"; done
  exit 1
fi
exit "$status"
