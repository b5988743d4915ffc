#!/usr/bin/env bash
# What the log says is so (README "Usage"): on a terminal the progress bar replaces the per-frame
# lines (-v prints them above it), off a terminal one line a frame; a frame that is the bind to
# float32 precision (data/elbow/elbow.pc2's first sample, the bind pose) is reported at rest and
# comes back unchanged; a frame with no free vertex (a one-face patch) gives no energy figure.
# Usage: SKINSLIDE=path/to/skinslide tests/cli/logs.sh
set -u
source "$(dirname "$0")/harness.sh"
cd "$root"
require_tools /usr/bin/script
py=/usr/bin/python3
elbow=(--patch data/elbow/patch.txt data/elbow/bind.obj data/elbow/frames/*.obj)

# --- a terminal -----------------------------------------------------------------------------------
script -qec "'$bin' -j 1 ${elbow[*]} -o '$tmp/tty'" /dev/null >"$tmp/tty.txt" 2>&1
sed 's/\r/\n/g; s/\x1b\[K//g' "$tmp/tty.txt" >"$tmp/tty_lines.txt"
check "on a terminal: the bar" grep -qE '\] [0-9]+/5 frames +[0-9.]+ frames/s' "$tmp/tty_lines.txt"
check "... instead of the per-frame lines" bash -c "! grep -q 'elbow.000[1-5].obj: 1 patch' '$tmp/tty_lines.txt'"
check "... then the bind's line and the summary" bash -c \
  "grep -q 'bind.obj: 1 patch, 288 sliding' '$tmp/tty_lines.txt' && grep -q '5 frames slid' '$tmp/tty_lines.txt'"
script -qec "'$bin' -v -j 1 ${elbow[*]} -o '$tmp/tty_v'" /dev/null >"$tmp/tty_v.txt" 2>&1
check "-v on a terminal: the per-frame lines" \
  [ "$(sed 's/\r/\n/g' "$tmp/tty_v.txt" | grep -c 'elbow.000[1-5].obj: 1 patch')" -eq 5 ]
"$bin" -j 1 "${elbow[@]}" -o "$tmp/file" 2>"$tmp/file.txt"
check "off a terminal: a line a frame, no bar" bash -c \
  "[ \$(grep -c 'elbow.000[1-5].obj: 1 patch' '$tmp/file.txt') -eq 5 ] && ! grep -q 'frames/s' '$tmp/file.txt'"

# --- a frame at rest ------------------------------------------------------------------------------
for method in elastic paper; do
  "$bin" --method $method -j 1 --patch data/elbow/patch.txt data/elbow/bind.obj data/elbow/elbow.pc2 \
    -o "$tmp/pc2_$method" 2>"$tmp/pc2_$method.txt"
  check "$method: the PC2's first sample (the bind in float32) is at rest" \
    grep -qF "elbow.pc2 sample 0 (elbow.0001): 1 patch, at rest (the bind to float32 precision), unchanged" \
    "$tmp/pc2_$method.txt"
  check "$method: ... with no energy figure" bash -c "! grep 'sample 0' '$tmp/pc2_$method.txt' | grep -q 'energy'"
  check "$method: ... and comes back unchanged, bit for bit" $py - "$tmp/pc2_$method/elbow.pc2" <<'PY'
import sys
a, b = open("data/elbow/elbow.pc2", "rb").read(), open(sys.argv[1], "rb").read()
n = 32 + 1056 * 12
assert a[:n] == b[:n], "sample 0 changed"
assert a[n:] != b[n:], "the other samples slide"
PY
done
check "the OBJ frame equal to the bind: at rest too, its file unchanged byte for byte" bash -c \
  "grep -qF 'elbow.0001.obj: 1 patch, at rest' '$tmp/file.txt' && cmp data/elbow/frames/elbow.0001.obj '$tmp/file/elbow.0001.obj'"

# --- no free vertex -------------------------------------------------------------------------------
echo 0 >"$tmp/one_face.txt"
"$bin" -j 1 --patch "$tmp/one_face.txt" data/elbow/bind.obj data/elbow/frames/elbow.000[45].obj \
  -o "$tmp/none" 2>"$tmp/none.txt"
check "a patch with no free vertex: no energy figure" bash -c "! grep -q 'energy' '$tmp/none.txt'"
check "... but what happened" grep -qF 'elbow.0004.obj: 1 patch, no free vertex: nothing slides' "$tmp/none.txt"

# --- --window: a run's ends and a window's cost -------------------------------------------------
win=(--patch data/elbow/patch.txt data/elbow/bind.obj)
"$bin" -q -j 1 --window 1 "${win[@]}" data/elbow/frames/elbow.000[234].obj -o "$tmp/cut" 2>"$tmp/cut.txt"
check "--window, frames 2-4 of 1-5 given: a warning, even with -q, with what to pass instead" grep -qF \
  "skinslide: warning: --window 1: the frames given start at data/elbow/frames/elbow.0002.obj with data/elbow/frames/elbow.0001.obj beside it and end at data/elbow/frames/elbow.0004.obj with data/elbow/frames/elbow.0005.obj beside it: the windows there are cut short where a run of the whole sequence has neighbours, so these frames are not what that run writes. Give the whole sequence and this chunk: --window 1 --frames 2-4 data/elbow/frames/elbow.*.obj" "$tmp/cut.txt"
check "... once" [ "$(grep -c 'window' "$tmp/cut.txt")" -eq 1 ]
"$bin" -j 1 --window 1 --frames 2-3 "${win[@]}" data/elbow/frames/*.obj -o "$tmp/chunk" 2>"$tmp/chunk.txt"
check "--window, --frames 2-3 of the 5 given: the chunk's neighbours told, once" bash -c \
  "[ \$(grep -c 'are a chunk of the 5 given: 2 frames beside them are relaxed for their windows, not written' '$tmp/chunk.txt') -eq 1 ]"
"$bin" -j 1 --window 1 "${win[@]}" data/elbow/frames/*.obj -o "$tmp/whole" 2>"$tmp/whole.txt"
check "--window, the whole sequence: nothing said of its ends" bash -c "! grep -qE 'chunk|warning' '$tmp/whole.txt'"
"$bin" -j 1 --window 4 --window-ends cycle "${win[@]}" data/elbow/frames/*.obj -o "$tmp/costly" \
  --report "$tmp/costly.json" 2>"$tmp/costly.txt"
check "frames whose window costs ten points: counted on the summary line, with what to do" grep -qF \
  "5 frames slid (2 not converged; 1 whose --window mean costs ten points of energy or more, 'X% without the window' on their lines: try a smaller --window, --window-ends one-sided if the shot is not a loop, or no window for separate poses)" "$tmp/costly.txt"
check "... as many as the lines that say so" [ "$(grep -c 'without the window (its frames' "$tmp/costly.txt")" -eq 1 ]
check "... and in the report's totals" $py - "$tmp/costly.json" <<'PY'
import json, sys
assert json.load(open(sys.argv[1]))["totals"]["window_costly"] == 1
PY
"$bin" -j 1 "${win[@]}" data/elbow/frames/*.obj -o "$tmp/nowin" --report "$tmp/nowin.json" 2>/dev/null
check "... a report without a window has no such key" bash -c "! grep -q window_costly '$tmp/nowin.json'"

finish logs
