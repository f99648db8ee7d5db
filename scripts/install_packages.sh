#!/usr/bin/env bash
# Installs the Debian packages given as arguments that are not installed yet (apt-get, as root
# or with sudo). Used by setup.sh (everything rlrun needs) and fuzz.sh (clang, libFuzzer).
#   scripts/install_packages.sh PACKAGE...
#   scripts/install_packages.sh --list-missing PACKAGE...   # only print those not installed
set -euo pipefail
list_only=""
if [[ ${1:-} == --list-missing ]]; then list_only=1; shift; fi
missing=()
for p in "$@"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [[ -n $list_only ]]; then echo "${missing[*]}"; exit 0; fi
((${#missing[@]})) || exit 0
echo "installing ${missing[*]}"
SUDO=""
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  SUDO=sudo
fi
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
