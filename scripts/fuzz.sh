#!/usr/bin/env bash
# Builds a libFuzzer target with clang (-fsanitize=fuzzer,address,undefined) and runs it.
# Usage: scripts/fuzz.sh obj|patch|gltf|pc2|mdd SECONDS [libFuzzer options...]
# The seed corpus is tests/fuzz/corpus/TARGET (read only); new inputs go to
# build-fuzz/corpus/TARGET, crashes to build-fuzz/crashes/TARGET. A crashing input belongs in
# tests/fuzz/regressions/TARGET once fixed (tests/fuzz/regressions_test.cpp parses each file).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
target=${1:?usage: scripts/fuzz.sh obj|patch|gltf|pc2|mdd SECONDS}
seconds=${2:?usage: scripts/fuzz.sh obj|patch|gltf|pc2|mdd SECONDS}
shift 2
case $target in obj | patch | gltf | pc2 | mdd) ;; *) echo "fuzz.sh: unknown target '$target' (obj, patch, gltf, pc2, mdd)" >&2; exit 2 ;; esac

SKINSLIDE_FUZZ_DEPS=1 "$root/scripts/deps.sh"
build=${SKINSLIDE_FUZZ_BUILD_DIR:-$root/build-fuzz}
if [ ! -f "$build/CMakeCache.txt" ]; then
  CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSKINSLIDE_FUZZ=ON -DSKINSLIDE_BUILD_TESTS=OFF -DSKINSLIDE_BUILD_BENCH=OFF \
    -DSKINSLIDE_SANITIZE=fuzzer-no-link,address,undefined >/dev/null
fi
cmake --build "$build" --target "fuzz_$target" -j"${SKINSLIDE_JOBS:-2}"

corpus=$build/corpus/$target
crashes=$build/crashes/$target
mkdir -p "$corpus" "$crashes"
# Dictionaries guide the mutations towards the formats' keywords.
dict=()
[ -f "$root/tests/fuzz/$target.dict" ] && dict=(-dict="$root/tests/fuzz/$target.dict")
cd "$crashes"
exec "$build/tests/fuzz/fuzz_$target" "$corpus" "$root/tests/fuzz/corpus/$target" "${dict[@]}" \
  -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 -timeout=10 \
  -print_final_stats=1 -artifact_prefix="$crashes/" "$@"
