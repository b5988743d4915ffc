#!/usr/bin/env bash
# Identical bytes on every farm: outputs do not depend on --threads (1, 2, 8), on running the
# frames all together, one at a time or in reverse order, on which run it is, nor on splitting a
# shot into --frames chunks run side by side (xargs -P) as a render farm does, as OBJ frames or
# as a point cache whose chunks are joined (`skinslide join`); with --window (and a loop's
# --window-ends cycle) too. And a run killed
# with SIGKILL leaves each output either as it was before or complete, never partial. The default
# method (elastic) throughout; thread counts, order and the farm split with --method paper too.
# Usage: SKINSLIDE=path/to/skinslide tests/cli/farm.sh
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
# shellcheck source=require.sh
. "$root/tests/cli/require.sh"
require_program SKINSLIDE
require_tools /usr/bin/python3 xargs
bin=$SKINSLIDE
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$root"
failed=0
passed=0

check() {
  local what=$1
  shift
  if "$@" >/dev/null 2>"$tmp/check.err"; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAIL: $what" >&2
    sed 's/^/    /' "$tmp/check.err" >&2
  fi
}

# Same file names and bytes in two folders, and at least `n` files.
same_tree() {
  local a=$1 b=$2 n=$3
  [ "$(find "$a" -type f | wc -l)" -ge "$n" ] || { echo "$a has fewer than $n files" >&2; return 1; }
  diff -r "$a" "$b" >&2
}

# A shot of 24 frames numbered 1-24 (the sample frames over and over, under farm-style names).
shot=$tmp/shot
mkdir -p "$shot"
mapfile -t sample < <(ls data/elbow/frames/*.obj)
for ((f = 1; f <= 24; f++)); do
  ln -s "$root/${sample[$(((f - 1) % ${#sample[@]}))]}" "$shot/$(printf 'arm.%04d.obj' "$f")"
done
frames=("$shot"/arm.*.obj)
slide() { "$bin" -q --patch data/elbow/patch.txt data/elbow/bind.obj "$@"; }

# --- determinism ---------------------------------------------------------------------------------
check "whole shot, --threads 1" slide -j 1 -o "$tmp/t1" "${frames[@]}"
for t in 2 8; do
  check "whole shot, --threads $t" slide -j "$t" -o "$tmp/t$t" "${frames[@]}"
  check "--threads 1 and $t give identical bytes" same_tree "$tmp/t1" "$tmp/t$t" 24
done
check "a second run" slide -j 2 -o "$tmp/again" "${frames[@]}"
check "two runs give identical bytes" same_tree "$tmp/t1" "$tmp/again" 24
reversed=()
for ((i = ${#frames[@]} - 1; i >= 0; i--)); do reversed+=("${frames[i]}"); done
check "reversed order" slide -j 2 -o "$tmp/rev" "${reversed[@]}"
check "reversed order gives identical bytes" same_tree "$tmp/t1" "$tmp/rev" 24
for f in "${frames[@]}"; do slide -j 1 -o "$tmp/single" "$f" || echo "FAIL: $f alone" >&2; done
check "one frame at a time gives identical bytes" same_tree "$tmp/t1" "$tmp/single" 24
# The sample frames repeat: equal inputs, equal outputs (a frame does not see its neighbours).
check "frames 1 and 6 (same input) give the same bytes" cmp "$tmp/t1/arm.0001.obj" "$tmp/t1/arm.0006.obj"
check "frames 1 and 2 (different inputs) differ" bash -c "! cmp -s '$tmp/t1/arm.0001.obj' '$tmp/t1/arm.0002.obj'"

# The paper's method too: thread counts, reversed order and a farm split give the same bytes.
check "whole shot, --method paper --threads 1" slide --method paper -j 1 -o "$tmp/p1" "${frames[@]}"
check "whole shot, --method paper --threads 8" slide --method paper -j 8 -o "$tmp/p8" "${frames[@]}"
check "--method paper: --threads 1 and 8 give identical bytes" same_tree "$tmp/p1" "$tmp/p8" 24
check "--method paper: reversed order" slide --method paper -j 2 -o "$tmp/prev" "${reversed[@]}"
check "--method paper: reversed order gives identical bytes" same_tree "$tmp/p1" "$tmp/prev" 24
check "--method paper: the methods differ" bash -c "! cmp -s '$tmp/p1/arm.0003.obj' '$tmp/t1/arm.0003.obj'"

# --- a task pinned to some cores -----------------------------------------------------------------
# A farm node runs several tasks, each pinned to its share of the cores (taskset, cpusets): -j 0
# (the default) takes the cores in the task's affinity, not every core of the node.
if command -v taskset >/dev/null && taskset -c 0 true 2>/dev/null; then
  taskset -c 0 "$bin" -v --patch data/elbow/patch.txt -o "$tmp/pinned" data/elbow/bind.obj \
    "${frames[@]:0:4}" 2>"$tmp/pinned.log"
  check "-j 0 pinned to one core runs one frame at a time" \
    grep -qx '  4 frames, 1 at a time (-j 0: the cores this task may use)' "$tmp/pinned.log"
  check "pinned, the bytes are the whole run's" cmp "$tmp/t1/arm.0004.obj" "$tmp/pinned/arm.0004.obj"
fi

# --- farm split ---------------------------------------------------------------------------------
# As OpenCue or Deadline cut a shot of frames 1-24 into chunks of 10: 1-10, 11-20, 21-30 (the
# last chunk runs past the shot's end and is clamped). Each task gets every frame file and its
# --frames range; the tasks run side by side into one output folder.
printf '%s\n' 1-10 11-20 21-30 >"$tmp/chunks"
check "the chunks run side by side (xargs -P 3)" \
  xargs -P 3 -I RANGE "$bin" -q -j 1 --frames RANGE -o "$tmp/farm" --patch data/elbow/patch.txt \
  data/elbow/bind.obj "${frames[@]}" <"$tmp/chunks"
check "the farm split gives the whole run's bytes" same_tree "$tmp/t1" "$tmp/farm" 24
check "the chunks run side by side (xargs -P 3, --method paper)" \
  xargs -P 3 -I RANGE "$bin" -q -j 1 --method paper --frames RANGE -o "$tmp/pfarm" --patch data/elbow/patch.txt \
  data/elbow/bind.obj "${frames[@]}" <"$tmp/chunks"
check "the farm split gives the whole run's bytes (--method paper)" same_tree "$tmp/p1" "$tmp/pfarm" 24
# Steps and lists pick exactly the frames they name.
check "--frames 1-24:5,3,20-21" slide -o "$tmp/step" --frames 1-24:5,3,20-21 "${frames[@]}"
check "--frames 1-24:5,3,20-21 writes frames 1 3 6 11 16 20 21" test \
  "$(cd "$tmp/step" && echo *)" = "arm.0001.obj arm.0003.obj arm.0006.obj arm.0011.obj arm.0016.obj arm.0020.obj arm.0021.obj"
for f in "$tmp/step"/*; do
  check "$(basename "$f") from --frames is the whole run's" cmp "$f" "$tmp/t1/$(basename "$f")"
done

# --- a point cache split into chunks ------------------------------------------------------------
# The same shot as one PC2 cache (frames 1-24): each chunk is a cache of its own
# (shot.0001-0010.pc2, ...; the last clamped to 0021-0024), and `skinslide join` makes the whole
# shot's cache from them, byte for byte the one-task run's.
/usr/bin/python3 "$(dirname "$0")/objs_to_pc2.py" "$tmp/shot.pc2" "${frames[@]}"
check "the whole cache, one task" slide -j 2 -o "$tmp/cache1" "$tmp/shot.pc2"
check "the cache's chunks run side by side (xargs -P 3)" \
  xargs -P 3 -I RANGE "$bin" -q -j 1 --frames RANGE -o "$tmp/cachefarm" --patch data/elbow/patch.txt \
  data/elbow/bind.obj "$tmp/shot.pc2" <"$tmp/chunks"
check "the chunks are named by their frames" test "$(cd "$tmp/cachefarm" && echo *)" = \
  "shot.0001-0010.pc2 shot.0011-0020.pc2 shot.0021-0024.pc2"
check "skinslide join" "$bin" join -q "$tmp"/cachefarm/shot.*-*.pc2
check "the joined chunks are the one-task cache, byte for byte" cmp "$tmp/cache1/shot.pc2" "$tmp/cachefarm/shot.pc2"
check "the slid cache is not the input" bash -c "! cmp -s '$tmp/shot.pc2' '$tmp/cache1/shot.pc2'"

# --- --window: each frame written with its neighbours ------------------------------------------
# With --window 2 frame f depends on frames f-2..f+2 of the sequence given (by frame number): the
# same bytes still for any thread count, the order the files are given in and a farm split,
# since every task is given the whole shot and picks its chunk with --frames.
check "--window 2, --threads 1" slide --window 2 -j 1 -o "$tmp/w1" "${frames[@]}"
check "--window 2, --threads 8" slide --window 2 -j 8 -o "$tmp/w8" "${frames[@]}"
check "--window 2: --threads 1 and 8 give identical bytes" same_tree "$tmp/w1" "$tmp/w8" 24
check "--window 2: reversed order" slide --window 2 -j 2 -o "$tmp/wrev" "${reversed[@]}"
check "--window 2: reversed order gives identical bytes" same_tree "$tmp/w1" "$tmp/wrev" 24
check "--window 2: the chunks run side by side (xargs -P 3)" \
  xargs -P 3 -I RANGE "$bin" -q -j 1 --window 2 --frames RANGE -o "$tmp/wfarm" \
  --patch data/elbow/patch.txt data/elbow/bind.obj "${frames[@]}" <"$tmp/chunks"
check "--window 2: the farm split gives the whole run's bytes" same_tree "$tmp/w1" "$tmp/wfarm" 24
check "--window 0 is no window" slide --window 0 -j 2 -o "$tmp/w0" "${frames[@]}"
check "--window 0 gives the run's bytes without it" same_tree "$tmp/t1" "$tmp/w0" 24
check "--window 2: frames 2 and 7 (same input, other neighbours) differ" \
  bash -c "! cmp -s '$tmp/w1/arm.0002.obj' '$tmp/w1/arm.0007.obj'"
check "--window 2: the whole cache, one task" slide --window 2 -j 2 -o "$tmp/wcache1" "$tmp/shot.pc2"
check "--window 2: the cache's chunks run side by side (xargs -P 3)" \
  xargs -P 3 -I RANGE "$bin" -q -j 1 --window 2 --frames RANGE -o "$tmp/wcachefarm" \
  --patch data/elbow/patch.txt data/elbow/bind.obj "$tmp/shot.pc2" <"$tmp/chunks"
check "--window 2: skinslide join" "$bin" join -q "$tmp"/wcachefarm/shot.*-*.pc2
check "--window 2: the joined chunks are the one-task cache, byte for byte" \
  cmp "$tmp/wcache1/shot.pc2" "$tmp/wcachefarm/shot.pc2"
check "--window 2: the cache is not the one without a window" \
  bash -c "! cmp -s '$tmp/cache1/shot.pc2' '$tmp/wcache1/shot.pc2'"
# --window-ends cycle: the shot is a loop, frame 24 followed by frame 1. Only the windows that
# reach past an end change: frames 2, 23 and 24 (reach 2; frame 1 is data/elbow's frame at the
# bind, written as it is either way); the rest are the one-sided run's.
check "--window-ends cycle, --threads 1" slide --window 2 --window-ends cycle -j 1 -o "$tmp/c1" "${frames[@]}"
check "--window-ends cycle, reversed, --threads 8" \
  slide --window 2 --window-ends cycle -j 8 -o "$tmp/crev" "${reversed[@]}"
check "--window-ends cycle: reversed and 8 threads give identical bytes" same_tree "$tmp/c1" "$tmp/crev" 24
check "--window-ends cycle: the chunks run side by side (xargs -P 3)" \
  xargs -P 3 -I RANGE "$bin" -q -j 1 --window 2 --window-ends cycle --frames RANGE \
  -o "$tmp/cfarm" --patch data/elbow/patch.txt data/elbow/bind.obj "${frames[@]}" <"$tmp/chunks"
check "--window-ends cycle: the farm split gives the whole run's bytes" same_tree "$tmp/c1" "$tmp/cfarm" 24
for f in 0002 0023 0024; do
  check "--window-ends cycle: frame $f (its window wraps) differs from one-sided" \
    bash -c "! cmp -s '$tmp/w1/arm.$f.obj' '$tmp/c1/arm.$f.obj'"
done
check "--window-ends cycle: frames 3-22 are the one-sided run's" bash -c \
  "for f in \$(seq -f '%04g' 3 22); do cmp -s '$tmp/w1/arm.'\$f'.obj' '$tmp/c1/arm.'\$f'.obj' || exit 1; done"

# --- SIGKILL mid-run ----------------------------------------------------------------------------
# The output folder starts with an older complete version of every output (the unslid frame).
# Runs are killed at 10% .. 90% of a run's length; after each kill every output must be the old
# file or the new one byte for byte. Temporary files (.NAME.tmp.XXXXXX) of the writes in flight
# may remain: a killed process cannot clean up; they are counted, never picked up by a glob.
big=$tmp/big
mkdir -p "$big"
for ((f = 1; f <= 120; f++)); do
  ln -s "$root/${sample[$(((f - 1) % ${#sample[@]}))]}" "$big/$(printf 'arm.%04d.obj' "$f")"
done
start=$(date +%s%N)
check "a 120-frame run" slide -j 2 -o "$tmp/bigref" "$big"/*.obj
run_ms=$((($(date +%s%N) - start) / 1000000))
mixed=0
leftovers=0
for pct in 10 30 50 70 90; do
  out=$tmp/kill$pct
  mkdir -p "$out"
  for f in "$big"/*.obj; do cp "$f" "$out/$(basename "$f")"; done
  # The binary itself in the background (not the shell function, whose subshell would take the kill).
  "$bin" -q -j 2 -o "$out" --patch data/elbow/patch.txt data/elbow/bind.obj "$big"/*.obj &
  pid=$!
  sleep "$(awk -v ms="$run_ms" -v p="$pct" 'BEGIN { printf "%.3f", ms * p / 100000 }')"
  kill -KILL "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  old=0 new=0 bad=0
  for f in "$big"/*.obj; do
    name=$(basename "$f")
    if cmp -s "$out/$name" "$tmp/bigref/$name"; then
      new=$((new + 1))
    elif cmp -s "$out/$name" "$f"; then
      old=$((old + 1))
    else
      bad=$((bad + 1))
      echo "    $out/$name is neither the old file nor the new one" >&2
    fi
  done
  leftovers=$((leftovers + $(find "$out" -name '.*.tmp.*' | wc -l)))
  echo "farm: killed at $pct%: $old old, $new new, $bad partial" >&2
  check "killed at $pct%: every output old or new" test "$bad" -eq 0
  [ "$old" -gt 0 ] && [ "$new" -gt 0 ] && mixed=$((mixed + 1))
done
# Without a kill that lands mid-run the check above proves nothing.
check "at least one kill landed mid-run (old and new outputs side by side)" test "$mixed" -ge 1
echo "farm: kills left $leftovers temporary files in total (run of ${run_ms} ms)"

echo "farm: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
