#!/usr/bin/env bash
# Builds the fuzz targets (fuzz/) with clang's libFuzzer, ASan and UBSan into build-fuzz/ and
# runs each for RUNS executions. Installs clang-14 and libclang-rt-14-dev (libFuzzer and the
# sanitizer runtimes) when they are missing, as scripts/setup.sh does for the rest.
#   scripts/fuzz.sh                   # every target, 1 000 000 executions each
#   scripts/fuzz.sh 50000 fuzz_model  # some targets, fewer executions
#   FUZZ_JOBS=2 scripts/fuzz.sh       # libFuzzer -fork=2: two processes per target
#   TMPDIR=/var/tmp scripts/fuzz.sh   # where the targets build their files (default /dev/shm)
#   FUZZ_TIMEOUT=10 scripts/fuzz.sh   # on a busy machine: libFuzzer's timeout is wall time;
#                                     # then replay with -timeout=1 (see the end of this file)
# New inputs go to build-fuzz/corpus/<target> (the committed seeds in fuzz/corpus/ stay as
# they are); a crash, sanitizer report, hang (> 1 s) or allocation over 2 GiB stops the target
# and writes the input to build-fuzz/artifacts/. Replay one with build-fuzz/fuzz/<target> FILE.
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS=${1:-1000000}
shift || true
TARGETS=("$@")
((${#TARGETS[@]})) || TARGETS=(fuzz_config fuzz_model fuzz_npy fuzz_journal fuzz_zoo fuzz_run_dir fuzz_export)

CXX_FUZZ=${CXX_FUZZ:-clang++-14}
[[ -n "${RLRUN_SKIP_INSTALL:-}" ]] || scripts/install_packages.sh clang-14 libclang-rt-14-dev

# The sanitizers (RLRUN_FUZZ implies -fsanitize=address,undefined) instrument everything;
# tests are not needed here.
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="$CXX_FUZZ" \
  -DRLRUN_FUZZ=ON -DRLRUN_BUILD_TESTS=OFF ${CMAKE_CXX_COMPILER_LAUNCHER:+-DCMAKE_CXX_COMPILER_LAUNCHER=$CMAKE_CXX_COMPILER_LAUNCHER} >/dev/null
cmake --build build-fuzz --target "${TARGETS[@]}"

declare -A DICT=([fuzz_config]=config.dict [fuzz_model]=model.dict [fuzz_npy]=model.dict [fuzz_journal]=journal.dict [fuzz_zoo]=zoo.dict [fuzz_run_dir]=run_dir.dict)
declare -A SEEDS=([fuzz_config]="fuzz/corpus/config configs" [fuzz_model]=fuzz/corpus/model [fuzz_npy]=fuzz/corpus/npy [fuzz_journal]=fuzz/corpus/journal [fuzz_zoo]="fuzz/corpus/zoo tests/data/zoo" [fuzz_run_dir]=fuzz/corpus/run_dir)
DICT[fuzz_export]=export.dict
SEEDS[fuzz_export]=fuzz/corpus/export
mkdir -p build-fuzz/artifacts
# The run-directory and journal targets build files in a private temporary directory for every
# input: on a RAM file system they run about 1.7 times as fast (fuzz_run_dir: 176 -> 300 exec/s).
if [[ -z "${TMPDIR:-}" && -d /dev/shm && -w /dev/shm ]]; then export TMPDIR=/dev/shm; fi
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
for target in "${TARGETS[@]}"; do
  mkdir -p "build-fuzz/corpus/$target"
  echo "fuzz: $target, $RUNS executions"
  start=$(date +%s)
  set +e
  # shellcheck disable=SC2086
  build-fuzz/fuzz/"$target" -runs="$RUNS" -timeout="${FUZZ_TIMEOUT:-1}" -rss_limit_mb=2048 -max_len=65536 \
    -dict="fuzz/corpus/${DICT[$target]}" -print_final_stats=1 \
    -artifact_prefix="build-fuzz/artifacts/$target-" ${FUZZ_JOBS:+-fork=$FUZZ_JOBS} \
    "build-fuzz/corpus/$target" ${SEEDS[$target]} >"build-fuzz/$target.log" 2>&1
  status=$?
  set -e
  grep -E "^#[0-9]+ *(INITED|DONE)|stat::|ERROR|SUMMARY|Test unit written|==[0-9]+==" "build-fuzz/$target.log" | head -40 || true
  echo "fuzz: $target exit $status after $(( $(date +%s) - start )) s (log: build-fuzz/$target.log)"
  [[ $status -eq 0 ]] || exit "$status"
  # Every input the run kept, once more, with the 1 s limit: no input may take that long.
  build-fuzz/fuzz/"$target" -runs=0 -timeout=1 -rss_limit_mb=2048 -print_final_stats=1 \
    "build-fuzz/corpus/$target" ${SEEDS[$target]} 2>&1 | grep -E "slowest_unit_time_sec|ERROR" || true
done
