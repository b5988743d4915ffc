#!/usr/bin/env bash
# FRAME sequences (README "Usage", "Point caches"): a BIND named as a member of its FRAME sequence
# is refused (exit 2, as a forgotten bind) unless --bind-is-frame, while a bind whose positions
# merely equal a frame's is slid; any OBJ or glTF sequence is written as one PC2 or MDD cache
# (--format pc2|mdd, -o naming the cache or its folder): --no-slide converts data/elbow's frames
# into data/elbow/elbow.pc2 byte for byte, a slid sequence's cache holds its slid frames rounded to
# float32 once, glTF frames make the cache --animation writes, --frames makes a chunk that joins,
# MDD times are the frame numbers over --fps, and a failed frame leaves no cache.
# Usage: SKINSLIDE=path/to/skinslide tests/cli/sequences.sh
set -u
source "$(dirname "$0")/harness.sh"
cd "$root"
py=/usr/bin/python3
patch=(--patch data/elbow/patch.txt)
frames=(data/elbow/frames/*.obj)

# --- the bind forgotten ---------------------------------------------------------------------------
check "a BIND named as the FRAMEs' first is refused (2)" \
  expect_exit 2 "$tmp/forgot" "${patch[@]}" "${frames[@]}"
check "the refusal says why and how to accept it" \
  grep -qF "BIND data/elbow/frames/elbow.0001.obj is named as a frame of the sequence it comes with (data/elbow/frames/elbow.0002.obj, ...): is the bind mesh missing? Give the bind before the frames, or --bind-is-frame" "$tmp/stderr"
check "the refused run wrote nothing" [ ! -e "$tmp/forgot" ]
check "--bind-is-frame takes it" "$bin" -q --bind-is-frame -o "$tmp/meant" "${patch[@]}" "${frames[@]}"
check "... and slides the other four frames" [ "$(ls "$tmp/meant" | wc -l)" -eq 4 ]
printf 'bind-is-frame = true\n' >"$tmp/meant.toml"
check "--bind-is-frame in a config file" \
  "$bin" -q --config "$tmp/meant.toml" -o "$tmp/meant_cfg" "${patch[@]}" "${frames[@]}"
check "a bind equal to a frame but not named as one is slid (data/elbow: frame 1 is the bind pose)" \
  "$bin" -q -o "$tmp/slid" "${patch[@]}" data/elbow/bind.obj "${frames[@]}"

# --- a sequence as one cache ----------------------------------------------------------------------
check "--no-slide --format pc2 -o shot.pc2 converts OBJ frames" \
  "$bin" -q --no-slide --format pc2 -o "$tmp/shot.pc2" "${patch[@]}" data/elbow/bind.obj "${frames[@]}"
check "... into data/elbow/elbow.pc2 byte for byte (frames 1-5: startFrame 1, sampleRate 1)" \
  cmp "$tmp/shot.pc2" data/elbow/elbow.pc2
check "-o a folder: the cache is named after the frames (elbow.pc2)" \
  "$bin" -q --no-slide --format pc2 -o "$tmp/conv" "${patch[@]}" data/elbow/bind.obj "${frames[@]}"
check "... and is the same file" cmp "$tmp/conv/elbow.pc2" data/elbow/elbow.pc2
check "the cache is all the folder holds (no temporary left)" [ "$(ls -A "$tmp/conv")" = elbow.pc2 ]

"$bin" -q --format pc2 -o "$tmp/slid.pc2" "${patch[@]}" data/elbow/bind.obj "${frames[@]}"
"$bin" -q --no-slide --format pc2 -o "$tmp/slid_objs.pc2" "${patch[@]}" data/elbow/bind.obj "$tmp"/slid/*.obj
check "a slid sequence's cache is its slid OBJ frames rounded to float32 once, byte for byte" \
  cmp "$tmp/slid.pc2" "$tmp/slid_objs.pc2"
check "... and compares the same as meshes with the slid cache of elbow.pc2" \
  "$bin" compare -q --bind data/elbow/bind.obj "$tmp/slid.pc2" "$tmp/slid_objs.pc2"

rig=(--patch data/elbow/rig_patch.txt)
"$bin" -q "${rig[@]}" --animation bend --format glb -o "$tmp/glb" data/elbow/rig.glb
"$bin" -q "${rig[@]}" --animation bend --format pc2 -o "$tmp/rig" data/elbow/rig.glb
check "glTF frames: their cache is the one --animation writes, byte for byte" bash -c \
  "'$bin' -q --no-slide --format pc2 -o '$tmp/glb.pc2' ${rig[*]} data/elbow/rig.glb '$tmp'/glb/*.glb &&
   cmp '$tmp/glb.pc2' '$tmp/rig/rig.pc2'"

"$bin" -q --no-slide --format pc2 --frames 2-3 -o "$tmp/chunks" "${patch[@]}" data/elbow/bind.obj "${frames[@]}"
"$bin" -q --no-slide --format pc2 --frames 4-5 -o "$tmp/chunks" "${patch[@]}" data/elbow/bind.obj "${frames[@]}"
"$bin" -q --no-slide --format pc2 --frames 1 -o "$tmp/chunks" "${patch[@]}" data/elbow/bind.obj "${frames[@]}"
check "--frames writes chunks named by their frames" \
  test -f "$tmp/chunks/elbow.0002-0003.pc2" -a -f "$tmp/chunks/elbow.0001-0001.pc2"
check "... that join into the whole sequence's cache" bash -c \
  "'$bin' join -q '$tmp'/chunks/elbow.*-*.pc2 -o '$tmp/joined' && cmp '$tmp/joined/elbow.pc2' data/elbow/elbow.pc2"

check "--format mdd --fps 24: an MDD cache" \
  "$bin" -q --no-slide --format mdd --fps 24 -o "$tmp/shot.mdd" "${patch[@]}" data/elbow/bind.obj "${frames[@]}"
check "... its times the frame numbers over 24, its points the PC2's (big-endian)" $py - "$tmp/shot.mdd" <<'PY'
import struct, sys
mdd = open(sys.argv[1], "rb").read()
pc2 = open("data/elbow/elbow.pc2", "rb").read()
samples, points = struct.unpack(">ii", mdd[:8])
assert (samples, points) == (5, 1056), (samples, points)
times = struct.unpack(">5f", mdd[8:28])
assert times == tuple(struct.unpack("f", struct.pack("f", n / 24))[0] for n in range(1, 6)), times
n = samples * points * 3
assert struct.unpack(">%df" % n, mdd[28:]) == struct.unpack("<%df" % n, pc2[32:])
PY

mkdir -p "$tmp/bad"
cp data/elbow/frames/elbow.000[1-4].obj "$tmp/bad/"
head -n 100 data/elbow/frames/elbow.0005.obj >"$tmp/bad/elbow.0005.obj"
check "a bad frame in the sequence fails the run (3)" \
  expect_exit 3 "$tmp/bad_out" --format pc2 "${patch[@]}" data/elbow/bind.obj "$tmp"/bad/*.obj
check "... and leaves no cache, not even a part of one" \
  bash -c "[ ! -e '$tmp/bad_out' ] || [ -z \"\$(ls -A '$tmp/bad_out')\" ]"

finish sequences
