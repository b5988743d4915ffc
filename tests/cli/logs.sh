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
check "... instead of the per-frame lines" bash -c "! grep -q 'elbow.000[1-5].obj: 1 patches' '$tmp/tty_lines.txt'"
check "... then the bind's line and the summary" bash -c \
  "grep -q 'bind.obj: 1 patches, 288 sliding' '$tmp/tty_lines.txt' && grep -q '5 frames slid' '$tmp/tty_lines.txt'"
script -qec "'$bin' -v -j 1 ${elbow[*]} -o '$tmp/tty_v'" /dev/null >"$tmp/tty_v.txt" 2>&1
check "-v on a terminal: the per-frame lines" \
  [ "$(sed 's/\r/\n/g' "$tmp/tty_v.txt" | grep -c 'elbow.000[1-5].obj: 1 patches')" -eq 5 ]
"$bin" -j 1 "${elbow[@]}" -o "$tmp/file" 2>"$tmp/file.txt"
check "off a terminal: a line a frame, no bar" bash -c \
  "[ \$(grep -c 'elbow.000[1-5].obj: 1 patches' '$tmp/file.txt') -eq 5 ] && ! grep -q 'frames/s' '$tmp/file.txt'"

# --- a frame at rest ------------------------------------------------------------------------------
for method in elastic paper; do
  "$bin" --method $method -j 1 --patch data/elbow/patch.txt data/elbow/bind.obj data/elbow/elbow.pc2 \
    -o "$tmp/pc2_$method" 2>"$tmp/pc2_$method.txt"
  check "$method: the PC2's first sample (the bind in float32) is at rest" \
    grep -qF "elbow.pc2 sample 0 (elbow.0001): 1 patches, at rest (the bind to float32 precision), unchanged" \
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
  "grep -qF 'elbow.0001.obj: 1 patches, at rest' '$tmp/file.txt' && cmp data/elbow/frames/elbow.0001.obj '$tmp/file/elbow.0001.obj'"

# --- no free vertex -------------------------------------------------------------------------------
echo 0 >"$tmp/one_face.txt"
"$bin" -j 1 --patch "$tmp/one_face.txt" data/elbow/bind.obj data/elbow/frames/elbow.000[45].obj \
  -o "$tmp/none" 2>"$tmp/none.txt"
check "a patch with no free vertex: no energy figure" bash -c "! grep -q 'energy' '$tmp/none.txt'"
check "... but what happened" grep -qF 'elbow.0004.obj: 1 patches, no free vertex: nothing slides' "$tmp/none.txt"

finish logs
