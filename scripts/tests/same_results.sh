#!/usr/bin/env bash
# Trains every shipped config (configs/*.yaml) with seed 1 using two rlrun binaries and
# compares the models' tensors byte for byte: a refactoring must not change results.
#   scripts/tests/same_results.sh OLD_RLRUN NEW_RLRUN [CONFIG...]
# OLD_RLRUN may be a directory of model files saved by an earlier call (KEEP_MODELS=DIR keeps
# this call's models there as <config>.zip), so the old build need not exist any more.
# Prints one line per config (same / DIFFERENT, with the first differing tensor) and exits 1
# when any differs. Threads: --threads 1 (results are identical with 2; 1 leaves a core free).
set -euo pipefail
cd "$(dirname "$0")/../.."
old=${1:?usage: scripts/tests/same_results.sh OLD_RLRUN|MODEL_DIR NEW_RLRUN [CONFIG...]}
new=${2:?usage: scripts/tests/same_results.sh OLD_RLRUN|MODEL_DIR NEW_RLRUN [CONFIG...]}
shift 2
configs=("$@")
((${#configs[@]})) || configs=(configs/*.yaml)
export SUMO_HOME=${SUMO_HOME:-/usr/share/sumo}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

train() {  # binary config out_dir -> path of model.zip
  "$1" --threads 1 train "$2" --seed 1 --out "$3" >"$3.log" 2>&1 ||
    { echo "training $2 with $1 failed:" >&2; tail -5 "$3.log" >&2; return 1; }
  find "$3" -name model.zip -path '*seed1/model.zip' | head -1
}

# The .npy members (weights, optimizer-free model state, normalisation statistics).
tensors() {
  python3 - "$1" <<'EOF'
import sys, zipfile, hashlib
with zipfile.ZipFile(sys.argv[1]) as z:
    for name in sorted(z.namelist()):
        if name.endswith(".npy"):
            print(name, hashlib.sha256(z.read(name)).hexdigest())
EOF
}

status=0
for config in "${configs[@]}"; do
  name=$(basename "$config" .yaml)
  if [[ -d $old ]]; then
    old_model=$old/$name.zip
  else
    old_model=$(train "$old" "$config" "$work/old_$name")
  fi
  new_model=$(train "$new" "$config" "$work/new_$name")
  if [[ -n ${KEEP_MODELS:-} ]]; then mkdir -p "$KEEP_MODELS" && cp "$new_model" "$KEEP_MODELS/$name.zip"; fi
  if diff <(tensors "$old_model") <(tensors "$new_model") >"$work/diff_$name"; then
    echo "same       $name ($(tensors "$new_model" | wc -l) tensors)"
  else
    echo "DIFFERENT  $name: $(grep '^[<>]' "$work/diff_$name" | head -1 | cut -c3- | cut -d' ' -f1)"
    status=1
  fi
done
exit $status
