#!/usr/bin/env bash
# Writes tests/data/mujoco/gymnasium_model_hashes.txt: for each model rlrun ships
# (scenarios/mujoco/*.xml), the hash of the model MuJoCo compiles from Gymnasium's asset of the
# same name. The test "MuJoCo task models compile to Gymnasium's" compiles rlrun's file and
# compares: equal hashes mean the same bodies, joints, geoms, actuators, options and visuals,
# value for value (the hash covers MuJoCo's whole binary model, mj_saveModel).
#   scripts/data/make_mujoco_model_hashes.sh GYMNASIUM_ASSETS_DIR
# GYMNASIUM_ASSETS_DIR: gymnasium/envs/mujoco/assets of Gymnasium 1.0.0 (a source checkout or
# an installed package). Needs libmujoco-dev and a C++ compiler.
set -euo pipefail
assets=${1:?usage: scripts/data/make_mujoco_model_hashes.sh GYMNASIUM_ASSETS_DIR}
here=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# The same hash as tests/envs/mujoco/mujoco_model_hash.hpp: FNV-1a (64 bit) of the binary model.
cat >"$tmp/hash.cpp" <<'CPP'
#include <mujoco/mujoco.h>
#include <cstdint>
#include <cstdio>
#include <vector>
int main(int argc, char** argv) {
  char error[1024] = "";
  mjModel* m = mj_loadXML(argv[1], nullptr, error, sizeof error);
  if (!m) { std::fprintf(stderr, "%s: %s\n", argv[1], error); return 1; }
  std::vector<unsigned char> bytes(static_cast<size_t>(mj_sizeModel(m)));
  mj_saveModel(m, nullptr, bytes.data(), static_cast<int>(bytes.size()));
  uint64_t hash = 14695981039346656037ull;
  for (unsigned char b : bytes) { hash ^= b; hash *= 1099511628211ull; }
  std::printf("%016llx %zu\n", static_cast<unsigned long long>(hash), bytes.size());
  mj_deleteModel(m);
}
CPP
c++ -O1 -o "$tmp/hash" "$tmp/hash.cpp" -lmujoco
out=$here/tests/data/mujoco/gymnasium_model_hashes.txt
{
  echo "# file hash(FNV-1a of mj_saveModel) bytes, of Gymnasium 1.0.0's assets on MuJoCo $(dpkg-query -W -f='${Version}' libmujoco-dev 2>/dev/null || echo '?')"
  echo "# made by scripts/data/make_mujoco_model_hashes.sh"
  for model in "$here"/scenarios/mujoco/*.xml; do
    name=$(basename "$model")
    echo "$name $("$tmp/hash" "$assets/$name")"
  done
} >"$out"
cat "$out"
