#!/usr/bin/env bash
# scripts/test.sh says, before it builds or installs anything, which clients the tests would
# install (Blender, Slurm) and which tests need them; with SKINSLIDE_NO_INSTALL=1 it says they
# will not be, and a test needing one skips (exit 77) naming it, without calling scripts/deps.sh.
# Checked on a copy of the scripts, on a PATH holding no blender nor sbatch, with cmake, ctest and
# deps.sh replaced by stubs that log their calls: nothing is built or installed.
# Usage: tests/cli/install_notice.sh
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
repo=$tmp/repo
mkdir -p "$repo/scripts" "$repo/tests/cli" "$repo/build" "$tmp/bin"
cp "$root"/scripts/{build,test}.sh "$repo/scripts/"
cp "$root"/tests/cli/cannot.sh "$repo/tests/cli/"
# Each stub logs its call to $tmp/calls and to stderr (where the notice must come first).
for stub in "$repo/scripts/deps.sh" "$tmp/bin/cmake" "$tmp/bin/ctest"; do
  printf '#!/bin/sh\necho "%s $*" >>"%s"\necho "stub: %s $*" >&2\n' "${stub##*/}" "$tmp/calls" \
    "${stub##*/}" >"$stub"
done
# The commands the scripts use, and no blender, sbatch nor munged.
for tool in bash sh dirname grep cat nproc env; do ln -s "$(command -v "$tool")" "$tmp/bin/$tool"; done
chmod +x "$repo/scripts"/*.sh "$tmp/bin"/*
failed=0
fail() { echo "FAIL: $*" >&2; failed=1; }

# notice [VAR=VALUE...]: scripts/test.sh's stderr, run with VARs set; its calls in $tmp/calls.
notice() {
  : >"$tmp/calls"
  (cd "$repo" && env -u SKINSLIDE_BUILD_DIR -u SKINSLIDE_NO_INSTALL PATH="$tmp/bin" "$@" \
    bash scripts/test.sh 2>&1 >/dev/null) || fail "scripts/test.sh failed"
}
said=$(notice)
sed 's/^/    /' <<<"$said"
grep -q "^test.sh: missing here, installed by those tests when they run" <<<"$said" ||
  fail "no notice of what the tests install"
grep -q "^  blender.*: cli_blender_cache, blender_addon" <<<"$said" || fail "Blender's tests not named"
grep -q "^  slurm-wlm munge.*: cli_slurm" <<<"$said" || fail "Slurm's test not named"
grep -q "SKINSLIDE_NO_INSTALL=1 scripts/test.sh runs without installing them" <<<"$said" ||
  fail "the way not to install is not said"
grep -q "^stub: deps.sh" <<<"$said" && grep -q "^stub: ctest" <<<"$said" ||
  fail "test.sh did not go on to deps.sh and ctest"
[[ "$(head -n 1 <<<"$said")" == "test.sh: missing here"* ]] || fail "something ran before the notice"
said=$(notice SKINSLIDE_NO_INSTALL=1)
sed 's/^/    /' <<<"$said"
grep -q "not installed (SKINSLIDE_NO_INSTALL=1): those tests skip, naming what is missing" <<<"$said" ||
  fail "SKINSLIDE_NO_INSTALL=1 not told"

# A test that would install: with SKINSLIDE_NO_INSTALL=1 it skips, naming the package, and
# deps.sh is not called.
: >"$tmp/calls"
skipped=$(cd "$repo" && env -u SKINSLIDE_REQUIRE_SHARED SKINSLIDE_NO_INSTALL=1 PATH="$tmp/bin" \
  bash -c '. tests/cli/cannot.sh; install_or_cannot blender; echo installed')
rc=$?
echo "    $skipped"
[ $rc -eq 77 ] || fail "install_or_cannot with SKINSLIDE_NO_INSTALL=1: exit $rc, not 77 (skip)"
grep -q "^SKIP: blender not installed, and SKINSLIDE_NO_INSTALL=1" <<<"$skipped" ||
  fail "the skip does not name blender"
[ ! -s "$tmp/calls" ] || fail "deps.sh called with SKINSLIDE_NO_INSTALL=1: $(cat "$tmp/calls")"
# Without it, deps.sh is asked for the package.
(cd "$repo" && env -u SKINSLIDE_NO_INSTALL PATH="$tmp/bin" bash -c '. tests/cli/cannot.sh; install_or_cannot blender') ||
  fail "install_or_cannot failed with deps.sh succeeding"
grep -q "^deps.sh blender$" "$tmp/calls" || fail "install_or_cannot did not call deps.sh blender"
[ $failed -eq 0 ] && echo "install_notice: test.sh names the clients it would install and their tests; SKINSLIDE_NO_INSTALL=1 skips them"
exit $failed
