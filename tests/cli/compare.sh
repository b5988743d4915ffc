#!/usr/bin/env bash
# `skinslide compare A B` on real outputs (README "Tests"): data/elbow slid twice (the same, exit
# 0), one coordinate's last digit changed (the same within the default tolerance, 1e-6 of the
# diagonal; different at --tolerance 0), the other method (different, exit 1, the frames and
# vertices named), a missing frame and mismatched counts (exit 3, naming the files), point caches
# with and without --bind, a farm chunk against the whole shot (--common: folders and caches), two
# meshes' frames in one folder (each in its own diagonal), the JSON report, usage errors (2) and a
# report that cannot be written (4). Every case's figures are printed: the log shows what compare
# says.
# Usage: SKINSLIDE=path/to/skinslide tests/cli/compare.sh
set -u
source "$(dirname "$0")/harness.sh"
cd "$root"
elbow=(--patch data/elbow/patch.txt data/elbow/bind.obj)
frames=(data/elbow/frames/*.obj)

# compares CODE PATTERN ARGS...: `skinslide compare ARGS` exits CODE and its stderr holds PATTERN;
# stdout stays empty. The stderr is kept in $tmp/said and shown.
compares() {
  local code=$1 pattern=$2
  shift 2
  "$bin" compare "$@" >"$tmp/stdout" 2>"$tmp/said"
  local rc=$?
  sed 's/^/    /' "$tmp/said"
  [ "$rc" -eq "$code" ] || { echo "exit $rc, expected $code" >&2; return 1; }
  [ ! -s "$tmp/stdout" ] || { echo "wrote to stdout" >&2; return 1; }
  [ -z "$pattern" ] || grep -qF -- "$pattern" "$tmp/said" || { echo "stderr lacks '$pattern'" >&2; return 1; }
}

"$bin" -q -j 1 "${elbow[@]}" "${frames[@]}" -o "$tmp/a"
"$bin" -q -j 2 "${elbow[@]}" "${frames[@]}" -o "$tmp/b"
echo "identical runs:"
check "two runs of a shot are the same (exit 0)" compares 0 "5 frames, the same" "$tmp/a" "$tmp/b"
check "-q says nothing when they are" compares 0 "" -q "$tmp/a" "$tmp/b"
check "...nothing at all" test ! -s "$tmp/said"

# One coordinate of a slid vertex (the first `v` line the slide changed) written differently, as
# another build may write it: MODE digit, its last digit one off (17 digits: often the same
# double); MODE bit, the next double up (one bit in the last place).
changed() {  # changed MODE OUT_DIR: a copy of $tmp/b with elbow.0003.obj so changed; prints the line
  cp -r "$tmp/b" "$2"
  /usr/bin/python3 - "$1" data/elbow/frames/elbow.0003.obj "$2/elbow.0003.obj" <<'PY'
import math, sys
mode, frame, slid = sys.argv[1], open(sys.argv[2]).read().split("\n"), sys.argv[3]
lines = open(slid).read().split("\n")
n = next(i for i, (f, s) in enumerate(zip(frame, lines)) if s.startswith("v ") and f != s)
tokens = lines[n].split()
if mode == "digit":
    tokens[3] = tokens[3][:-1] + str((int(tokens[3][-1]) + 9) % 10)
else:
    tokens[3] = repr(math.nextafter(float(tokens[3]), math.inf))
lines[n] = " ".join(tokens)
open(slid, "w").write("\n".join(lines))
print(n + 1)
PY
}
line=$(changed digit "$tmp/last_digit")
echo "a last digit changed: line $line, $(sed -n "${line}p" "$tmp/b/elbow.0003.obj") -> $(sed -n "${line}p" "$tmp/last_digit/elbow.0003.obj"):"
check "the bytes differ" bash -c "! cmp -s '$tmp/b/elbow.0003.obj' '$tmp/last_digit/elbow.0003.obj'"
check "a last digit changed is the same mesh" compares 0 "5 frames, the same" "$tmp/a" "$tmp/last_digit"
line=$(changed bit "$tmp/last_bit")
echo "a last bit changed: line $line, $(sed -n "${line}p" "$tmp/b/elbow.0003.obj") -> $(sed -n "${line}p" "$tmp/last_bit/elbow.0003.obj"):"
check "a last bit is the same mesh within the default tolerance" \
  compares 0 "5 frames, the same" -v "$tmp/a" "$tmp/last_bit"
check "...and differs at --tolerance 0, naming the vertex's line" \
  compares 1 "differs: $tmp/a/elbow.0003.obj: largest distance" --tolerance 0 "$tmp/a" "$tmp/last_bit"
check "...the line of the changed vertex" grep -qF "($tmp/a/elbow.0003.obj:$line)" "$tmp/said"

echo "the other method:"
"$bin" -q --method paper "${elbow[@]}" "${frames[@]}" -o "$tmp/paper"
check "the paper method's slide differs (exit 1)" compares 1 "4 differ" "$tmp/a" "$tmp/paper"
check "...one line a differing frame, naming the vertex" \
  test "$(grep -c '^skinslide compare: differs: .* vertex [0-9]* (' "$tmp/said")" -eq 4
check "...the frame at rest (the bind pose) is not one of them" \
  bash -c "! grep -q 'differs: .*elbow.0001.obj' '$tmp/said'"

echo "missing frames and mismatched counts:"
cp -r "$tmp/b" "$tmp/fewer" && rm "$tmp/fewer/elbow.0004.obj"
check "a missing frame is refused (exit 3), named" \
  compares 3 "$tmp/a has 5 frames, $tmp/fewer 4; missing from $tmp/fewer: elbow.0004.obj" "$tmp/a" "$tmp/fewer"
cp -r "$tmp/b" "$tmp/other_mesh" && cp data/face/frames/face.0002.obj "$tmp/other_mesh/elbow.0002.obj"
check "a frame of another mesh is refused (exit 3), both files named" \
  compares 3 "$tmp/other_mesh/elbow.0002.obj: has 1069 vertices; $tmp/a/elbow.0002.obj has 1056" "$tmp/a" "$tmp/other_mesh"

echo "a farm chunk against the whole shot (--common):"
"$bin" -q --frames 2-4 "${elbow[@]}" "${frames[@]}" -o "$tmp/chunk_objs"
check "without --common a chunk is refused (exit 3), pointing at it" \
  compares 3 "missing from $tmp/chunk_objs: elbow.0001.obj, elbow.0005.obj (--common compares the frames both hold)" "$tmp/a" "$tmp/chunk_objs"
check "with --common the frames both hold are compared, the others named (exit 0)" \
  compares 0 "--common: 3 frames in both compared; left out 2 only in $tmp/a ($tmp/a/elbow.0001.obj, $tmp/a/elbow.0005.obj), 0 only in $tmp/chunk_objs" --common "$tmp/a" "$tmp/chunk_objs"
check "...the summary counts those 3" grep -qF "compare: 3 frames, the same" "$tmp/said"
check "...and a difference in them is still one (exit 1)" \
  compares 1 "1 differ" --common --tolerance 0 "$tmp/last_bit" "$tmp/chunk_objs"

echo "two meshes' frames in one folder:"
face=(--patch data/face/patch.txt data/face/bind.obj data/face/frames/*.obj)
"$bin" -q "${face[@]}" -o "$tmp/face_elastic"
"$bin" -q --method paper "${face[@]}" -o "$tmp/face_paper"
"$bin" compare -q --report "$tmp/face_alone.json" "$tmp/face_elastic" "$tmp/face_paper"
mkdir "$tmp/two_a" "$tmp/two_b"
cp "$tmp/a"/*.obj "$tmp/face_elastic"/*.obj "$tmp/two_a"
cp "$tmp/b"/*.obj "$tmp/face_paper"/*.obj "$tmp/two_b"
check "the face's frames differ, the elbow's do not (exit 1), each in its own diagonal" \
  compares 1 "of each frame's own diagonal, A's" --report "$tmp/two.json" "$tmp/two_a" "$tmp/two_b"
check "...the face's distances as when its frames are compared alone (not in the elbow's diagonal)" \
  /usr/bin/python3 - "$tmp/face_alone.json" "$tmp/two.json" <<'PY'
import json, os, sys
alone = {os.path.basename(f["a"]): f for f in json.load(open(sys.argv[1]))["frames"]}
both = {os.path.basename(f["a"]): f for f in json.load(open(sys.argv[2]))["frames"]}
assert len(both) == len(alone) + 5, (len(both), len(alone))
for name, f in alone.items():
    assert (both[name]["max_distance"], both[name]["diagonal"]) == (f["max_distance"], f["diagonal"]), (name, both[name], f)
assert [f["differs"] for n, f in both.items() if n.startswith("elbow")] == [False] * 5
print(f"    face frames: diagonals {sorted({f['diagonal'] for f in alone.values()})}, the elbow's "
      f"{both['elbow.0001.obj']['diagonal']}")
PY
check "...with the elbow's --bind the face's frames are refused (exit 3), both files named" \
  compares 3 "$tmp/two_a/face.0001.obj: has 1069 vertices; the bind (data/elbow/bind.obj) has 1056" --bind data/elbow/bind.obj "$tmp/two_a" "$tmp/two_b"

echo "glTF frames:"
rig=(--patch data/elbow/rig_patch.txt --animation bend data/elbow/rig.glb)
"$bin" -q -j 1 "${rig[@]}" -o "$tmp/ga"
"$bin" -q -j 2 "${rig[@]}" -o "$tmp/gb"
"$bin" -q --method paper "${rig[@]}" -o "$tmp/gp"
check "two runs' GLB frames are the same" compares 0 "5 frames, the same" "$tmp/ga" "$tmp/gb"
check "the paper method's GLB frames differ, the rest pose does not" compares 1 "4 differ" "$tmp/ga" "$tmp/gp"

echo "point caches:"
/usr/bin/python3 "$here/objs_to_pc2.py" "$tmp/shot.pc2" "${frames[@]}"
"$bin" -q -j 1 "${elbow[@]}" "$tmp/shot.pc2" -o "$tmp/ca"
"$bin" -q -j 2 "${elbow[@]}" "$tmp/shot.pc2" -o "$tmp/cb"
"$bin" -q --method paper "${elbow[@]}" "$tmp/shot.pc2" -o "$tmp/cp"
"$bin" -q --frames 1-4 "${elbow[@]}" "$tmp/shot.pc2" -o "$tmp/chunk"
check "two runs' caches are the same, faces unchecked without a bind" \
  compares 0 "faces not compared" "$tmp/ca/shot.pc2" "$tmp/cb/shot.pc2"
check "two output folders holding caches are the same" compares 0 "5 frames, the same" "$tmp/ca" "$tmp/cb"
check "with --bind the bind's diagonal and faces" \
  compares 1 "of the diagonal 8.485, data/elbow/bind.obj's)" --bind data/elbow/bind.obj "$tmp/ca/shot.pc2" "$tmp/cp/shot.pc2"
check "...a cache's sample named with its frame" grep -qF "differs: $tmp/ca/shot.pc2 sample 2 (frame 3)" "$tmp/said"
# A float32's last bit flipped: the z of point 600 of sample 4 (slid: the patch is points
# 320-671), as another build's rounding may leave it; in sample 4's own diagonal (the bent tube's,
# shorter than the bind's 8.485).
cp "$tmp/cb/shot.pc2" "$tmp/flipped.pc2"
/usr/bin/python3 - "$tmp/flipped.pc2" <<'PY'
import sys
at = 32 + (4 * 1056 + 600) * 12 + 8  # little-endian: the mantissa's lowest bit is the first byte's
with open(sys.argv[1], "r+b") as f:
    f.seek(at)
    low = f.read(1)[0]
    f.seek(at)
    f.write(bytes([low ^ 1]))
PY
check "a float32's last bit in a cache is the same mesh" \
  compares 0 "largest distance 3.242e-08" "$tmp/ca/shot.pc2" "$tmp/flipped.pc2"
check "...and differs at --tolerance 0" \
  compares 1 "differs: $tmp/ca/shot.pc2 sample 4 (frame 5): largest distance 3.242e-08" --tolerance 0 "$tmp/ca/shot.pc2" "$tmp/flipped.pc2"
check "a chunk against the whole shot: counts refused (exit 3)" \
  compares 3 "$tmp/chunk/shot.0001-0004.pc2: has 4 samples; $tmp/ca/shot.pc2 has 5" "$tmp/ca/shot.pc2" "$tmp/chunk/shot.0001-0004.pc2"
check "...with --common its 4 samples against the shot's, by frame number (exit 0)" \
  compares 0 "--common: 4 frames in both compared; left out 1 only in $tmp/ca/shot.pc2 ($tmp/ca/shot.pc2 sample 4 (frame 5)), 0 only in $tmp/chunk/shot.0001-0004.pc2" --common "$tmp/ca/shot.pc2" "$tmp/chunk/shot.0001-0004.pc2"

echo "the report:"
check "--report writes JSON" compares 1 "4 differ" --report "$tmp/r1.json" "$tmp/a" "$tmp/paper"
"$bin" compare -q --report "$tmp/r2.json" "$tmp/a" "$tmp/paper"
check "...the same bytes for the same inputs" cmp "$tmp/r1.json" "$tmp/r2.json"
check "...with every frame and the totals" /usr/bin/python3 - "$tmp/r1.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
assert list(r) == ["skinslide", "a", "b", "tolerance", "diagonal", "diagonal_from", "faces_checked",
                   "frames", "only_in_a", "only_in_b", "differing_frames", "largest", "same"], list(r)
assert r["diagonal"] is None and r["diagonal_from"] is None  # no --bind: each frame's own
assert all(f["diagonal"] > 0 for f in r["frames"]) and r["only_in_a"] == r["only_in_b"] == []
assert len(r["frames"]) == 5 and r["differing_frames"] == 4 and r["same"] is False
assert r["frames"][0]["differs"] is False and r["frames"][0]["max_distance"] == 0
assert all(f["max_distance"] > r["tolerance"] for f in r["frames"][1:])
assert r["largest"]["max_distance"] == max(f["max_distance"] for f in r["frames"])
PY

echo "usage and output errors:"
check "one output only is a usage error (exit 2)" compares 2 "B is required" "$tmp/a"
check "a folder against a cache is a usage error" compares 2 "are not alike" "$tmp/a" "$tmp/ca/shot.pc2"
check "--tolerance out of range" compares 2 "--tolerance" --tolerance -1 "$tmp/a" "$tmp/b"
check "a report that cannot be written (exit 4)" compares 4 "cannot" --report "$tmp/none/r.json" "$tmp/a" "$tmp/b"
finish compare
