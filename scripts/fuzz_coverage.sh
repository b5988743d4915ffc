#!/usr/bin/env bash
# Line and branch coverage that the fuzzing corpora reach in the readers: rebuilds the libFuzzer
# targets with clang's source-based coverage (no sanitizers), runs each once over its corpus
# (build-fuzz/corpus/TARGET from scripts/fuzz.sh, plus the seeds) and prints llvm-cov's report
# for the files each target exercises.
# Usage: scripts/fuzz_coverage.sh [obj|patch|gltf|pc2|mdd...]   (default: all five)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(obj patch gltf pc2 mdd)

SKINSLIDE_FUZZ_DEPS=1 "$root/scripts/deps.sh"
build=${SKINSLIDE_FUZZ_COVERAGE_DIR:-$root/build-fuzz-coverage}
corpora=${SKINSLIDE_FUZZ_BUILD_DIR:-$root/build-fuzz}/corpus
if [ ! -f "$build/CMakeCache.txt" ]; then
  CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release \
    -DSKINSLIDE_FUZZ=ON -DSKINSLIDE_BUILD_TESTS=OFF -DSKINSLIDE_BUILD_BENCH=OFF \
    -DSKINSLIDE_SANITIZE=fuzzer-no-link \
    -DCMAKE_CXX_FLAGS="-fprofile-instr-generate -fcoverage-mapping" \
    -DCMAKE_EXE_LINKER_FLAGS="-fprofile-instr-generate" >/dev/null
fi
for t in "${targets[@]}"; do
  cmake --build "$build" --target "fuzz_$t" -j"${SKINSLIDE_JOBS:-2}" >/dev/null
done

for t in "${targets[@]}"; do
  case $t in
    obj) files=(lib/io/obj_read.cpp lib/io/obj_rewrite.cpp lib/core/number_format.cpp) ;;
    patch) files=(lib/io/patch_file.cpp) ;;
    gltf) files=(lib/io/gltf/gltf_read.cpp lib/io/gltf/gltf_accessor.cpp) ;;
    pc2 | mdd) files=(lib/io/point_cache.cpp lib/io/cache_chunks.cpp) ;;
    *) echo "fuzz_coverage.sh: unknown target '$t' (obj, patch, gltf, pc2, mdd)" >&2; exit 2 ;;
  esac
  dirs=("$root/tests/fuzz/corpus/$t")
  [ -d "$corpora/$t" ] && dirs+=("$corpora/$t")
  rm -f "$build/$t.profraw"
  LLVM_PROFILE_FILE="$build/$t.profraw" "$build/tests/fuzz/fuzz_$t" -runs=0 "${dirs[@]}" \
    >"$build/$t.log" 2>&1
  llvm-profdata merge -sparse "$build/$t.profraw" -o "$build/$t.profdata"
  echo "== $t: $(find "${dirs[@]}" -type f | wc -l) inputs"
  llvm-cov report "$build/tests/fuzz/fuzz_$t" -instr-profile="$build/$t.profdata" "${files[@]/#/$root/}"
done
