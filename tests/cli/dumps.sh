#!/usr/bin/env bash
# End-to-end checks of --dump and --preview on data/: the files named as README "Dumps" says,
# readable by exrheader, the same bytes for --threads 1 and 2, and name clashes refused before
# anything is written.
# Usage: SKINSLIDE=path/to/skinslide tests/cli/dumps.sh
set -u
source "$(dirname "$0")/harness.sh"
require_tools exrheader

lists() {  # lists FILE PATTERN...: exrheader reads FILE and prints every PATTERN
  local out
  out=$(exrheader "$1" 2>&1) || { echo "$out" >&2; return 1; }
  shift
  for p in "$@"; do
    grep -qF -- "$p" <<<"$out" || { echo "'$p' not in exrheader output of $1" >&2; return 1; }
  done
}

cd "$root"
frames=(data/elbow/frames/elbow.0001.obj data/elbow/frames/elbow.0003.obj)
for t in 1 2; do
  check "runs with --dump and --preview, --threads $t" \
    "$bin" -q --threads "$t" --lookup-size 256 --preview-size 256 --patch data/elbow/patch.txt \
    data/elbow/bind.obj "${frames[@]}" -o "$tmp/t$t/slid" --dump "$tmp/t$t/dump" \
    --preview "$tmp/t$t/preview"
done
check "dump file names" [ "$(cd "$tmp/t1/dump" && ls | tr '\n' ' ')" = \
  "bind.patch000.geom.exr bind.patch000.id.exr elbow.0001.patch000.geom.exr elbow.0001.patch000.id.exr elbow.0003.patch000.geom.exr elbow.0003.patch000.id.exr " ]
check "preview file names" [ "$(cd "$tmp/t1/preview" && ls | tr '\n' ' ')" = \
  "elbow.0001.patch000.png elbow.0003.patch000.png " ]
check "--threads 1 and 2 give identical dumps and previews" diff -r "$tmp/t1" "$tmp/t2"
check "the slid frames do not depend on --dump" bash -c \
  "'$bin' -q --lookup-size 256 --patch data/elbow/patch.txt data/elbow/bind.obj ${frames[*]} \
   -o '$tmp/plain' && diff -r '$tmp/plain' '$tmp/t1/slid'"
check "exrheader reads the ID image" lists "$tmp/t1/dump/elbow.0003.patch000.id.exr" \
  "id, 32-bit unsigned integer" "(0 0) - (255 255)" 'skinslide.image (type string): "id"' \
  'skinslide.source (type string): "data/elbow/frames/elbow.0003.obj"' 'skinslide.method (type string): "elastic"'
check "exrheader reads the frame's geometry image" lists \
  "$tmp/t1/dump/elbow.0003.patch000.geom.exr" "A, 32-bit floating-point" \
  "P.X, 32-bit floating-point" "P.Y, 32-bit floating-point" "P.Z, 32-bit floating-point" \
  "slide.X, 32-bit floating-point" "slide.Y, 32-bit floating-point" 'skinslide.net (type string): "frame"'
check "the bind's geometry image has no slide field" bash -c \
  "! exrheader '$tmp/t1/dump/bind.patch000.geom.exr' | grep -q slide.X"

# A frame whose dumps would overwrite the bind's: usage error (2), nothing written.
mkdir -p "$tmp/clash"
cp data/elbow/frames/elbow.0003.obj "$tmp/clash/bind.obj"
"$bin" -q --patch data/elbow/patch.txt data/elbow/bind.obj "$tmp/clash/bind.obj" \
  -o "$tmp/clash/slid" --dump "$tmp/clash/dump" 2>"$tmp/stderr"
rc=$?
check "a frame named bind.obj with --dump exits 2" [ "$rc" -eq 2 ]
check "and says why" grep -q "would overwrite the bind's" "$tmp/stderr"
check "and writes nothing" bash -c "[ ! -e '$tmp/clash/slid' ] && [ ! -e '$tmp/clash/dump' ]"

finish dumps
