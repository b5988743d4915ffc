#!/usr/bin/env bash
# End-to-end checks of the skinslide command on data/: exit codes, outputs, golden files,
# determinism across thread counts, and that errors write nothing.
# Usage: SKINSLIDE=path/to/skinslide tests/cli/end_to_end.sh
set -u
source "$(dirname "$0")/harness.sh"

no_files() { [ -z "$(ls -A "$1" 2>/dev/null)" ]; }

cd "$root"
for case in elbow face; do
  frames=(data/$case/frames/*.obj)
  for t in 1 2; do
    check "$case runs with --threads $t" \
      "$bin" -q --threads "$t" --patch data/$case/patch.txt data/$case/bind.obj "${frames[@]}" -o "$tmp/$case.t$t"
  done
  check "$case writes one output per frame" [ "$(ls "$tmp/$case.t1" | wc -l)" -eq "${#frames[@]}" ]
  check "$case: --threads 1 and 2 give identical bytes" diff -r "$tmp/$case.t1" "$tmp/$case.t2"
  for f in "${frames[@]}"; do
    name=$(basename "$f")
    check "$case/$name matches its golden file" \
      /usr/bin/python3 "$here/compare_obj.py" "$here/golden/$case/$name" "$tmp/$case.t1/$name"
  done
  # Reversed frame order and a run of one frame give the same bytes for each frame.
  reversed=()
  for ((i = ${#frames[@]} - 1; i >= 0; i--)); do reversed+=("${frames[i]}"); done
  "$bin" -q --patch data/$case/patch.txt data/$case/bind.obj "${reversed[@]}" -o "$tmp/$case.rev"
  check "$case: reversed frame order gives the same bytes" diff -r "$tmp/$case.t1" "$tmp/$case.rev"
  "$bin" -q --patch data/$case/patch.txt data/$case/bind.obj "${frames[-1]}" -o "$tmp/$case.one"
  check "$case: a frame alone gives the same bytes" cmp "$tmp/$case.one/$(basename "${frames[-1]}")" \
    "$tmp/$case.t1/$(basename "${frames[-1]}")"
done

# A folded net: --density paper folds the elbow (hundreds of flipped triangles), where walks are
# blocked and overlapping triangles compete for a point. The golden files pin which one wins.
"$bin" -q --density paper --holes free --patch data/elbow/patch.txt data/elbow/bind.obj \
  data/elbow/frames/elbow.000{3,4}.obj -o "$tmp/elbow.paper"
for out in "$tmp"/elbow.paper/*.obj; do
  check "elbow --density paper: $(basename "$out") matches its golden file" \
    /usr/bin/python3 "$here/compare_obj.py" "$here/golden/elbow-paper/$(basename "$out")" "$out"
done

# Huge pages (the command restarts itself with glibc's request where the kernel waits for one)
# change where memory lies, never what is computed. The variable, set, also stops the restart.
GLIBC_TUNABLES=glibc.malloc.hugetlb=0 "$bin" -q --patch data/face/patch.txt data/face/bind.obj \
  data/face/frames/*.obj -o "$tmp/face.small_pages"
check "face: the same bytes without huge pages" diff -r "$tmp/face.t1" "$tmp/face.small_pages"

# The bind itself as a frame comes out byte-identical (nothing to slide).
cp data/face/bind.obj "$tmp/identity.obj"
"$bin" -q --patch data/face/patch.txt data/face/bind.obj "$tmp/identity.obj" -o "$tmp/identity"
check "an identity frame is written unchanged" cmp data/face/bind.obj "$tmp/identity/identity.obj"

# --no-slide (the I/O floor): every frame written byte for byte; --frame-solver cg and
# multigrid, and --locate image: the same results.
"$bin" -q --no-slide --patch data/elbow/patch.txt data/elbow/bind.obj data/elbow/frames/*.obj -o "$tmp/noslide"
check "--no-slide writes every frame unchanged" diff -r data/elbow/frames "$tmp/noslide"
"$bin" -q --frame-solver cg --patch data/face/patch.txt data/face/bind.obj data/face/frames/*.obj -o "$tmp/face.cg"
"$bin" -q -j 1 --frame-solver multigrid --patch data/face/patch.txt data/face/bind.obj data/face/frames/*.obj -o "$tmp/face.mg"
"$bin" -q -j 2 --frame-solver multigrid --patch data/face/patch.txt data/face/bind.obj data/face/frames/*.obj -o "$tmp/face.mg2"
check "--frame-solver multigrid: the same bytes with -j 1 and -j 2" diff -r "$tmp/face.mg" "$tmp/face.mg2"
"$bin" -q --locate image --patch data/face/patch.txt data/face/bind.obj data/face/frames/*.obj -o "$tmp/face.image"
for out in "$tmp"/face.image/*.obj; do
  check "--locate image: $(basename "$out") matches its golden file" \
    /usr/bin/python3 "$here/compare_obj.py" "$here/golden/face/$(basename "$out")" "$out"
done
for out in "$tmp"/face.cg/*.obj; do
  check "--frame-solver cg: $(basename "$out") matches its golden file" \
    /usr/bin/python3 "$here/compare_obj.py" "$here/golden/face/$(basename "$out")" "$out"
done

for out in "$tmp"/face.mg/*.obj; do
  check "--frame-solver multigrid: $(basename "$out") matches its golden file" \
    /usr/bin/python3 "$here/compare_obj.py" "$here/golden/face/$(basename "$out")" "$out"
done

# Only v lines change: every other line of a slid frame is the frame's own.
check "only v lines differ from the frame" bash -c \
  "diff <(grep -v '^v ' data/elbow/frames/elbow.0003.obj) <(grep -v '^v ' '$tmp/elbow.t1/elbow.0003.obj')"

# Errors: exit code per class, message, and no output written.
f=data/elbow/frames/elbow.0002.obj
check "--help exits 0" "$bin" --help >/dev/null
check "--version exits 0" bash -c "'$bin' --version | grep -q '^skinslide '"
check "unknown option is a usage error (2)" expect_exit 2 "$tmp/e1" --patch data/elbow/patch.txt --bogus data/elbow/bind.obj "$f"
check "missing frames is a usage error (2)" expect_exit 2 "$tmp/e2" --patch data/elbow/patch.txt data/elbow/bind.obj
check "missing bind file is an input error (3)" expect_exit 3 "$tmp/e3" --patch data/elbow/patch.txt "$tmp/none.obj" "$f"
printf '0-99999\n' >"$tmp/far.txt"
check "out-of-range patch face is an input error (3)" expect_exit 3 "$tmp/e4" --patch "$tmp/far.txt" data/elbow/bind.obj "$f"
check "a bad patch writes nothing" no_files "$tmp/e4"
head -c 20000 data/face/frames/face.0002.obj >"$tmp/cut.obj"
check "a truncated frame is an input error (3)" expect_exit 3 "$tmp/e5" --patch data/face/patch.txt data/face/bind.obj "$tmp/cut.obj"
check "the bad frame leaves no file" no_files "$tmp/e5"
check "a frame of another mesh is an input error (3)" expect_exit 3 "$tmp/e6" --patch data/elbow/patch.txt data/elbow/bind.obj data/face/bind.obj
touch "$tmp/afile"
check "an output folder that is a file is an output error (4)" expect_exit 4 "$tmp/afile" --patch data/elbow/patch.txt data/elbow/bind.obj "$f"
check "an output that would overwrite an input is refused (2)" expect_exit 2 data/elbow/frames --patch data/elbow/patch.txt data/elbow/bind.obj "$f"
check "the input is intact" cmp "$f" <(git -C "$root" show HEAD:"$f" 2>/dev/null || cat "$f")

finish end_to_end
