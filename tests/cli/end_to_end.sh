#!/usr/bin/env bash
# End-to-end checks of the skinslide command on data/: exit codes, outputs, golden files of the
# paper's method, what the default (elastic) method keeps and moves, determinism across thread
# counts with both methods, the options of one method refused with the other, and that errors
# write nothing.
# Usage: SKINSLIDE=path/to/skinslide tests/cli/end_to_end.sh
set -u
source "$(dirname "$0")/harness.sh"

no_files() { [ -z "$(ls -A "$1" 2>/dev/null)" ]; }

cd "$root"
# Both methods: outputs, identical bytes across thread counts, frame orders and runs of one
# frame. The paper's method (--method paper, with its defaults: density inverse, holes fill) must
# match the golden files; the default method (elastic) has no golden files yet (its numerics may
# still change), so its outputs are checked for what every slide guarantees (below).
for method in paper elastic; do
  flags=()
  [ "$method" = paper ] && flags=(--method paper)  # elastic: the default, given no --method
  for case in elbow face; do
    frames=(data/$case/frames/*.obj)
    out=$tmp/$case.$method
    for t in 1 2; do
      check "$case ($method) runs with --threads $t" \
        "$bin" -q ${flags[@]+"${flags[@]}"} --threads "$t" --patch data/$case/patch.txt data/$case/bind.obj \
        "${frames[@]}" -o "$out.t$t"
    done
    check "$case ($method) writes one output per frame" [ "$(ls "$out.t1" | wc -l)" -eq "${#frames[@]}" ]
    check "$case ($method): --threads 1 and 2 give identical bytes" diff -r "$out.t1" "$out.t2"
    if [ "$method" = paper ]; then
      for f in "${frames[@]}"; do
        name=$(basename "$f")
        check "$case/$name (paper) matches its golden file" \
          /usr/bin/python3 "$here/compare_obj.py" "$here/golden/$case/$name" "$out.t1/$name"
      done
    fi
    # Reversed frame order and a run of one frame give the same bytes for each frame.
    reversed=()
    for ((i = ${#frames[@]} - 1; i >= 0; i--)); do reversed+=("${frames[i]}"); done
    "$bin" -q ${flags[@]+"${flags[@]}"} --patch data/$case/patch.txt data/$case/bind.obj "${reversed[@]}" -o "$out.rev"
    check "$case ($method): reversed frame order gives the same bytes" diff -r "$out.t1" "$out.rev"
    "$bin" -q ${flags[@]+"${flags[@]}"} --patch data/$case/patch.txt data/$case/bind.obj "${frames[-1]}" -o "$out.one"
    check "$case ($method): a frame alone gives the same bytes" cmp "$out.one/$(basename "${frames[-1]}")" \
      "$out.t1/$(basename "${frames[-1]}")"
  done
done

# The default method's outputs, frame by frame: lines other than `v` lines are the frame's; the
# `v` lines of vertices outside the patch and on its loops (border and holes) are the frame's
# byte for byte; every coordinate is finite; a deformed frame's patch moves (some free vertex's
# line differs from the frame's) and a frame in the bind pose (elbow.0001) comes out unchanged.
for case in elbow face; do
  check "$case (elastic): loops and outside kept, deformed frames slid" /usr/bin/python3 - \
    data/$case/bind.obj data/$case/patch_plain.txt data/$case/frames "$tmp/$case.elastic.t1" <<'PY'
import math, os, sys
bind, patch, frames, out = sys.argv[1:5]
def vlines(lines):
    return [l for l in lines if l.startswith(b"v ")]
blines = open(bind, "rb").read().split(b"\n")
faces = [[int(t.split(b"/")[0]) - 1 for t in l.split()[1:]] for l in blines if l.startswith(b"f ")]
selected = [int(t) for l in open(patch) for t in l.split("#")[0].split()]
edges = {}
for f in selected:
    face = faces[f]
    for a, b in zip(face, face[1:] + face[:1]):
        e = (min(a, b), max(a, b))
        edges[e] = edges.get(e, 0) + 1
patch_vertices = {v for f in selected for v in faces[f]}
on_loops = {v for e, n in edges.items() if n == 1 for v in e}
free = patch_vertices - on_loops
n = len(vlines(blines))
kept = [v for v in range(n) if v not in free]
assert on_loops and free, (len(on_loops), len(free))
names = sorted(os.listdir(frames))
assert sorted(os.listdir(out)) == names, os.listdir(out)
for name in names:
    f = open(os.path.join(frames, name), "rb").read().split(b"\n")
    s = open(os.path.join(out, name), "rb").read().split(b"\n")
    assert len(f) == len(s), name
    assert [l for l in f if not l.startswith(b"v ")] == [l for l in s if not l.startswith(b"v ")], name
    fv, sv = vlines(f), vlines(s)
    for v in kept:
        assert fv[v] == sv[v], (name, "vertex %d (loop or outside the patch) moved" % v)
    for l in sv:
        assert all(math.isfinite(float(x)) for x in l.split()[1:4]), (name, l)
    moved = sum(fv[v] != sv[v] for v in free)
    if fv == vlines(blines):
        assert f == s, (name, "a frame in the bind pose changed")
    else:
        assert moved > 0, (name, "a deformed frame came out unchanged")
    print("%s: %d of %d free vertices moved, %d loop and outside vertices kept" % (name, moved, len(free), len(kept)))
PY
done

# The log names the method: the bind line, and per frame the paper's solver and fallbacks or
# the elastic relaxation's iterations and energy.
"$bin" --patch data/elbow/patch.txt data/elbow/bind.obj data/elbow/frames/elbow.0003.obj -o "$tmp/log.elastic" 2>"$tmp/log.txt"
check "the default log says elastic" bash -c "grep -q '288 sliding vertices (method elastic)' '$tmp/log.txt' &&
  grep -qE 'elbow.0003.obj: 1 patch, elastic [0-9]+ it, energy left [0-9.]+%, flips 0, max slide' '$tmp/log.txt' &&
  ! grep -q fallbacks '$tmp/log.txt'"
"$bin" --method paper --patch data/elbow/patch.txt data/elbow/bind.obj data/elbow/frames/elbow.0003.obj -o "$tmp/log.paper" 2>"$tmp/log.txt"
check "the paper's log says its density, solver and fallbacks" bash -c "
  grep -q '288 sliding vertices (method paper, density inverse, holes fill)' '$tmp/log.txt' &&
  grep -qE 'elbow.0003.obj: 1 patch, Cholesky, max slide [0-9.]+, 0 fallbacks' '$tmp/log.txt'"

# Options of one method are refused with the other (usage error, naming the option, nothing
# written); the elastic options run.
e=(--patch data/elbow/patch.txt data/elbow/bind.obj data/elbow/frames/elbow.0003.obj)
refused_option() {  # refused_option OPTION OUTDIR ARGS...: exit 2 naming OPTION, no output
  local option=$1 out=$2
  shift 2
  expect_exit 2 "$out" "$@" && grep -qF -- "$option: applies to --method" "$tmp/stderr" && no_files "$out" ||
    { echo "stderr: $(cat "$tmp/stderr")" >&2; return 1; }
}
check "--method elastic --density paper is refused (2)" refused_option --density "$tmp/m1" --method elastic --density paper "${e[@]}"
check "--corners with the default method is refused (2)" refused_option --corners "$tmp/m2" --corners 356,364,372,380 "${e[@]}"
for o in "--holes free" "--q-floor 0.01" "--frame-solver cg" "--cg-tolerance 1e-10" "--cg-max-iterations 50" "--locate image"; do
  check "$o with the default method is refused (2)" refused_option "${o%% *}" "$tmp/m3" $o "${e[@]}"
done
check "--method paper --max-iterations 5 is refused (2)" refused_option --max-iterations "$tmp/m4" --method paper --max-iterations 5 "${e[@]}"
check "--method paper --tolerance 1e-3 is refused (2)" refused_option --tolerance "$tmp/m5" --method paper --tolerance 1e-3 "${e[@]}"
check "an unknown method is a usage error (2)" expect_exit 2 "$tmp/m6" --method bogus "${e[@]}"
check "--method elastic --solver search --max-iterations 5 --tolerance 1e-3 runs" \
  "$bin" -q --method elastic --solver search --max-iterations 5 --tolerance 1e-3 "${e[@]}" -o "$tmp/m7"
refused_with_map() {  # refused_with_map OPTION OUTDIR ARGS...: exit 2 naming OPTION, no output
  local option=$1 out=$2
  shift 2
  expect_exit 2 "$out" "$@" && grep -qF -- "$option: applies to --solver search only" "$tmp/stderr" &&
    no_files "$out" || { echo "stderr: $(cat "$tmp/stderr")" >&2; return 1; }
}
for o in "--rotation-fits 2" "--max-iterations 5" "--tolerance 1e-3" "--ease-in 1" "--blend 1"; do
  check "$o with the default map is refused (2)" refused_with_map "${o%% *}" "$tmp/m8" $o "${e[@]}"
done
check "--method paper --density paper --corners runs" \
  "$bin" -q --method paper --density paper --corners 356,364,372,380 "${e[@]}" -o "$tmp/m8"

# A folded net: --density paper folds the elbow (hundreds of flipped triangles), where walks are
# blocked and overlapping triangles compete for a point. The golden files pin which one wins.
"$bin" -q --method paper --density paper --holes free --patch data/elbow/patch.txt data/elbow/bind.obj \
  data/elbow/frames/elbow.000{3,4}.obj -o "$tmp/elbow.paper-density"
for name in elbow.0003.obj elbow.0004.obj; do
  check "elbow --density paper: $name matches its golden file" \
    /usr/bin/python3 "$here/compare_obj.py" "$here/golden/elbow-paper/$name" "$tmp/elbow.paper-density/$name"
done

# Huge pages (the command restarts itself with glibc's request where the kernel waits for one)
# change where memory lies, never what is computed. The variable, set, also stops the restart.
GLIBC_TUNABLES=glibc.malloc.hugetlb=0 "$bin" -q --patch data/face/patch.txt data/face/bind.obj \
  data/face/frames/*.obj -o "$tmp/face.small_pages"
check "face: the same bytes without huge pages" diff -r "$tmp/face.elastic.t1" "$tmp/face.small_pages"

# The bind itself as a frame comes out byte-identical (nothing to slide).
cp data/face/bind.obj "$tmp/identity.obj"
"$bin" -q --patch data/face/patch.txt data/face/bind.obj "$tmp/identity.obj" -o "$tmp/identity"
check "an identity frame is written unchanged" cmp data/face/bind.obj "$tmp/identity/identity.obj"

# --no-slide (the I/O floor): every frame written byte for byte. The paper's --frame-solver cg
# and multigrid, and --locate image: the same results as its golden files.
"$bin" -q --no-slide --patch data/elbow/patch.txt data/elbow/bind.obj data/elbow/frames/*.obj -o "$tmp/noslide"
check "--no-slide writes every frame unchanged" diff -r data/elbow/frames "$tmp/noslide"
paper_face=(--method paper --patch data/face/patch.txt data/face/bind.obj data/face/frames/*.obj)
"$bin" -q --frame-solver cg "${paper_face[@]}" -o "$tmp/face.cg"
"$bin" -q -j 1 --frame-solver multigrid "${paper_face[@]}" -o "$tmp/face.mg"
"$bin" -q -j 2 --frame-solver multigrid "${paper_face[@]}" -o "$tmp/face.mg2"
check "--frame-solver multigrid: the same bytes with -j 1 and -j 2" diff -r "$tmp/face.mg" "$tmp/face.mg2"
"$bin" -q --locate image "${paper_face[@]}" -o "$tmp/face.image"
for variant in image:"--locate image" cg:"--frame-solver cg" mg:"--frame-solver multigrid"; do
  for f in data/face/frames/*.obj; do
    name=$(basename "$f")
    check "${variant#*:}: $name matches its golden file" \
      /usr/bin/python3 "$here/compare_obj.py" "$here/golden/face/$name" "$tmp/face.${variant%%:*}/$name"
  done
done

# Only v lines change: every other line of a slid frame is the frame's own.
check "only v lines differ from the frame" bash -c \
  "diff <(grep -v '^v ' data/elbow/frames/elbow.0003.obj) <(grep -v '^v ' '$tmp/elbow.elastic.t1/elbow.0003.obj')"

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
