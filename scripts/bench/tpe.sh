#!/usr/bin/env bash
# rlrun's TPE against Optuna 3.1's own (issue 23): both samplers, and random search as the
# floor, on Branin 2-D, Hartmann 6-D and a noisy 4-D quadratic, TRIALS trials, SEEDS seeds each;
# prints a Markdown table (median best, IQR, Mann-Whitney p of rlrun against Optuna) for
# docs/benchmarks.md.
#   scripts/bench/tpe.sh                        (after building: ninja -C build rlrun_tpe_bench)
#   SEEDS=20 TRIALS=100 SAMPLERS=tpe,random,tpe_univariate scripts/bench/tpe.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
seeds=${SEEDS:-20}
trials=${TRIALS:-100}
samplers=${SAMPLERS:-tpe,random}
build=${BUILD_DIR:-build}
python=${PYTHON:-/usr/bin/python3}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$build/bench/rlrun_tpe_bench" --seeds "$seeds" --trials "$trials" --samplers "$samplers" \
  >"$out/rlrun.tsv" 2>"$out/rlrun.log"
start=$(date +%s)
"$python" scripts/bench/tpe.py run --seeds "$seeds" --trials "$trials" --samplers "$samplers" \
  >"$out/optuna.tsv"
end=$(date +%s)
echo "rlrun: $(awk '{s += $(NF-1)} END {print s}' "$out/rlrun.log") s in total; Optuna: $((end - start)) s" >&2
cat "$out/rlrun.log" >&2
"$python" scripts/bench/tpe.py table "$out/rlrun.tsv" "$out/optuna.tsv"
if [[ -n "${KEEP:-}" ]]; then cp "$out"/*.tsv "$KEEP"/; fi
