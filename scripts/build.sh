#!/usr/bin/env bash
# Installs the dependencies (if missing) and builds skinslide into build/ (Release).
# Usage: scripts/build.sh [--target TARGET] [extra cmake -D options]
#   --target TARGET  build only that target (and what it needs), e.g. skinslide
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
targets=()
if [ "${1:-}" = --target ]; then
  targets=(--target "$2")
  shift 2
fi
"$root/scripts/deps.sh"
build=${SKINSLIDE_BUILD_DIR:-$root/build}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build" -j"$(nproc)" ${targets[@]+"${targets[@]}"}
