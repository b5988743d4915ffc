#!/usr/bin/env bash
# README's two commands share one build: scripts/demo.sh configures the build tree exactly as
# scripts/test.sh does (the same cmake options: a different -Werror or tests switch would make
# test.sh recompile everything demo.sh built) and builds the command only; test.sh then builds
# everything. Checked on copies of the three scripts with cmake, ctest, scripts/deps.sh and the
# built command replaced by stubs that log how they were called: nothing is built or installed.
# Usage: tests/cli/demo_build.sh
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
repo=$tmp/repo
mkdir -p "$repo/scripts" "$repo/build" "$tmp/bin"
cp "$root"/scripts/{build,demo,test}.sh "$repo/scripts/"
printf '#!/bin/sh\nexit 0\n' >"$repo/scripts/deps.sh"
printf '#!/bin/sh\nexit 0\n' >"$repo/build/skinslide"
for tool in cmake ctest; do
  printf '#!/bin/sh\necho "%s $*" >>"%s"\n' "$tool" "$tmp/calls" >"$tmp/bin/$tool"
done
chmod +x "$repo/scripts"/*.sh "$repo/build/skinslide" "$tmp/bin"/*

run() {  # run SCRIPT: its cmake calls, one a line
  : >"$tmp/calls"
  (cd "$repo" && env -u SKINSLIDE_BUILD_DIR PATH="$tmp/bin:$PATH" bash "scripts/$1" >/dev/null 2>&1) ||
    { echo "FAIL: scripts/$1 failed" >&2; exit 1; }
  cat "$tmp/calls"
}
demo=$(run demo.sh)
test=$(run test.sh)
failed=0
fail() { echo "FAIL: $*" >&2; failed=1; }
configure() { grep -- ' -S ' <<<"$1"; }
[ -n "$(configure "$demo")" ] || fail "demo.sh configures nothing: $demo"
[ "$(configure "$demo")" = "$(configure "$test")" ] ||
  fail "demo.sh and test.sh configure the build differently:
  demo: $(configure "$demo")
  test: $(configure "$test")"
grep -q -- '--build .* --target skinslide$' <<<"$demo" || fail "demo.sh does not build the command alone: $demo"
grep -- '--build' <<<"$test" | grep -q -- '--target' && fail "test.sh builds a single target: $test"
grep -q '^ctest ' <<<"$test" || fail "test.sh runs no ctest: $test"
[ $failed -eq 0 ] && echo "demo_build: demo.sh and test.sh configure one build the same way; demo builds the command only"
exit $failed
