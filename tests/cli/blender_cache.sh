#!/usr/bin/env bash
# A real client of skinslide's point caches, both ways: Debian's Blender 3.4 (installed when
# missing; a test tool, never a dependency of skinslide), headless.
#   1. Blender animates data/elbow's bind with its frames (shape keys) and writes shot.pc2 and
#      shot.mdd with its own exporters (the io_export_pc2 and io_shape_mdd add-ons).
#   2. skinslide reads each exactly as Blender evaluated it (--no-slide --format obj: every
#      coordinate the float32 Blender wrote), and slides it into a cache with the same header.
#   3. Blender's Mesh Cache modifier plays skinslide's slid caches: at every frame the evaluated
#      positions are skinslide's own slid positions (--format obj: doubles) rounded to float32,
#      exactly; blender_cache.py prints the largest difference (below half a float32 ulp).
# Exits 77 (skipped), saying why, where Blender cannot be installed or run; with
# SKINSLIDE_REQUIRE_SHARED=1 (CI) that is a failure instead.
# Usage: SKINSLIDE=path/to/skinslide tests/cli/blender_cache.sh
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
# shellcheck source=require.sh
. "$root/tests/cli/require.sh"
require_program SKINSLIDE
require_tools /usr/bin/python3
bin=$SKINSLIDE
blender=${BLENDER:-blender}
failed=0
passed=0

# shellcheck source=cannot.sh
. "$(dirname "$0")/cannot.sh"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

if ! command -v "$blender" >/dev/null; then
  install_or_cannot blender
  command -v "$blender" >/dev/null || cannot "blender is not on the PATH after installing it"
fi

check() {
  local what=$1
  shift
  if "$@" >"$tmp/check.out" 2>&1; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAIL: $what" >&2
    tail -n 20 "$tmp/check.out" | sed 's/^/    /' >&2
  fi
}

in_blender() {
  "$blender" -b --factory-startup -noaudio --python-exit-code 1 \
    --python "$root/tests/cli/blender_cache.py" -- "$@" >"$tmp/blender.log" 2>&1
  local rc=$?
  grep -E '^(export|play)' "$tmp/blender.log"
  [ "$rc" -eq 0 ] || { tail -n 20 "$tmp/blender.log"; return "$rc"; }
}

# same_positions OBJ_DIR FLOATS N: the OBJ files' v lines (in name order) are the little-endian
# float32 coordinates of FLOATS, exactly.
same_positions() {
  /usr/bin/python3 - "$@" <<'EOF'
import glob, sys
import numpy as np
objs = sorted(glob.glob(sys.argv[1] + "/*.obj"))
floats = np.fromfile(sys.argv[2], "<f4").reshape(int(sys.argv[3]), -1, 3)
assert len(objs) == len(floats), (len(objs), len(floats))
for path, want in zip(objs, floats):
    got = np.array([[float(t) for t in l.split()[1:4]] for l in open(path) if l.startswith("v ")])
    assert got.shape == want.shape, (path, got.shape, want.shape)
    assert np.array_equal(got, want.astype(np.float64)), (path, np.abs(got - want).max())
print(len(objs), "frames identical")
EOF
}

bind=$root/data/elbow/bind.obj
patch=$root/data/elbow/patch.txt
frames=("$root"/data/elbow/frames/*.obj)
n=${#frames[@]}
echo "blender_cache: $("$blender" -b --factory-startup --version 2>/dev/null | grep -m1 '^Blender')"
in_blender export "$tmp/blender" "$bind" "${frames[@]}" || cannot "Blender cannot run headless here: $(tail -n 1 "$tmp/blender.log")"
slide() { "$bin" -q -j 2 --patch "$patch" "$bind" "$@"; }
play=()
for ext in pc2 mdd; do
  cache=$tmp/blender/shot.$ext
  check "skinslide reads Blender's $ext" slide --no-slide --format obj -o "$tmp/read_$ext" "$cache"
  check "...every coordinate as Blender evaluated it" same_positions "$tmp/read_$ext" "$tmp/blender/evaluated.f32" "$n"
  check "skinslide slides Blender's $ext" slide -o "$tmp/slid" "$cache"
  header=$([ $ext = pc2 ] && echo 32 || echo $((8 + 4 * n)))
  check "the slid $ext has Blender's header, byte for byte" cmp -n "$header" "$cache" "$tmp/slid/shot.$ext"
  check "the slid $ext is not Blender's" bash -c "! cmp -s '$cache' '$tmp/slid/shot.$ext'"
  check "skinslide's own slid positions (--format obj)" slide --format obj -o "$tmp/own_$ext" "$cache"
  play+=("$tmp/slid/shot.$ext" "$tmp/own_$ext")
done
check "Blender's Mesh Cache modifier plays skinslide's PC2 and MDD as skinslide slid them" \
  in_blender play "$bind" "$n" "${play[@]}"
sed 's/^/blender_cache: /' "$tmp/check.out"
echo "blender_cache: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
