#!/usr/bin/env bash
# A run's start-up is linear in its number of frames (README "Farm"): planning and checking 2,000
# FRAME files looks at each file a few times, never each output against each input. Counted, not
# timed: the stat calls of `--no-slide --frames 1` over 2,000 frames (links to data/elbow's), at
# most kStatsPerFrame a frame plus a fixed kStatsFixed; a quadratic check makes millions and runs
# into the timeout. Timings are scripts/bench.sh --scale's.
# Usage: SKINSLIDE=path/to/skinslide tests/cli/scale.sh
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=require.sh
. "$here/require.sh"
require_program SKINSLIDE
require_tools strace timeout
root=$(cd "$here/../.." && pwd)
elbow=$root/data/elbow
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
frames=2000
kStatsPerFrame=4
kStatsFixed=400
mkdir -p "$tmp/frames"
for k in $(seq "$frames"); do
  ln -s "$elbow/frames/elbow.000$(((k - 1) % 5 + 1)).obj" "$(printf '%s/frames/elbow.%04d.obj' "$tmp" "$k")"
done
# LeakSanitizer cannot run under ptrace (a sanitizer build aborts): leaks are checked by the other
# runs of the suite, not this counted one.
if ! ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" timeout 120 strace -f -c -o "$tmp/calls" "$SKINSLIDE" -q --no-slide --frames 1 -j 1 \
  -o "$tmp/out" "$elbow/bind.obj" "$tmp"/frames/*.obj 2>"$tmp/stderr"; then
  echo "FAIL: the run of $frames frames failed or took over 120 s: $(cat "$tmp/stderr")" >&2
  exit 1
fi
stats=$(awk '$NF ~ /^(stat|lstat|newfstatat|fstatat64|statx)$/ {n += $4} END {print n + 0}' "$tmp/calls")
limit=$((kStatsPerFrame * frames + kStatsFixed))
if [ "$stats" -gt "$limit" ]; then
  echo "FAIL: $stats stat calls for $frames frames (at most $limit)" >&2
  exit 1
fi
[ -f "$tmp/out/elbow.0001.obj" ] || { echo "FAIL: frame 1 not written" >&2; exit 1; }
echo "scale: $stats stat calls for $frames frames (at most $limit)"
