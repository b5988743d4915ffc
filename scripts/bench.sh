#!/usr/bin/env bash
# Benchmarks skinslide: synthetic cases generated on the fly (a curved, unevenly stretched
# surface with three holes, bent at a joint by two-bone skinning; tests/bench/bench_case.cpp)
# and the ICT face of ../shared/data (neutral = bind, four expressions = frames).
#
#   scripts/bench.sh [-s "10000 100000 1000000"] [-f FRAMES] [-F FRAMES_BIG] [-r RUNS] [--no-ict]
#                    [--peers | --peers-only] [--peer-sizes "40000 100000 490000 1000000"]
#                    [--peer-frames N] [--peer-repeats N] [--peer-e2e-frames N]
#                    [--peer-e2e-frames-big N]
#   (FRAMES frames per case, default 20; FRAMES_BIG, default 4, from 400k vertices on)
#
# The main table is the paper method's (--method paper); the elastic method's is --peers'.
# Per case, medians over RUNS runs:
#   - stages (CPU time of one thread, tests/bench/bench_stages.cpp): bind read, bind set-up, and
#     per frame read, frame net, locate, transfer, write; the set-up and frame net also with
#     each net solver forced (--frame-solver cholesky and multigrid; the default is auto);
#   - end to end (wall clock of the command): frames/second with -j1 and -j2, the -j2 speed-up of
#     the frame loop alone (the time on the command's summary line, after the set-up), peak
#     memory, and the I/O floor: the same command with --no-slide (frames read, checked and
#     written unchanged).
# Every time is also given as a ratio to the I/O floor's time per frame (x floor).
# Prints a Markdown table; BENCH_DIR keeps the generated cases (default: a temporary folder).
#
# --peers: also the elastic method's table (the command's default), beside the peer a pipeline
# would use instead, Blender's Corrective Smooth modifier (delta mush; Debian's blender, installed
# by scripts/deps.sh when missing; a benchmark tool only), on the synthetic cases of --peer-sizes
# (default "40000 100000 490000 1000000"; cases are generated as above). Per case, one run each:
#   - Corrective Smooth (below 1M vertices), 10 iterations, one thread (blender -t 1), rest = the
#     bind, vertex group = the patch's free vertices, on the case's first frame
#     (scripts/corrective_smooth.py `time`): warm evaluations as in playback (the frame is an
#     animated shape key, scene.frame_set per time, the modifier's rest cache kept), medians of
#     --peer-repeats (default 9) evaluations of the scene; the same with the modifier off gives
#     the overhead (shape key mix, mesh copy), and "modifier" is the difference; "cold" is the
#     first evaluation (the rest's deltas computed); process CPU ms;
#   - skinslide's elastic method on the same frame, given --peer-frames times (default 1; 0:
#     Corrective Smooth alone): the `relax` stage of tests/bench/bench_stages.cpp (-m elastic),
#     thread CPU ms, with its Gauss-Newton steps, and its `slide_frame` (relax plus the transfer
#     of its result), medians; the ratio elastic relax / Corrective Smooth's modifier;
#   - the bind set-up of both methods (bench_stages -b, thread CPU ms);
#   - end to end: the command (bind + the first --peer-e2e-frames frames, default 20; from 400k
#     vertices --peer-e2e-frames-big, default 2) with -j1, wall seconds per frame, against the
#     same command with --no-slide (the I/O floor); peak memory with -j1 and with -j2.
# --peers-only: the peer table alone (no stage, command or ICT runs).
#
# --scale ["100 1000 10000"]: how a run's cost grows with its number of frames, alone (no other
# table; builds the command only; SKINSLIDE=path benchmarks that binary instead). data/elbow's
# bind and patch with N OBJ frames (links to its 5 frames, elbow.00001.obj ...) and one PC2
# cache of N samples (its 5 samples repeated). Per N, medians over RUNS runs, -j 1, wall clock:
#   - start-up: `--no-slide --frames 1` (the frames planned and checked, one frame copied; no
#     bind set-up), and `--frames 1` (the same with the bind's set-up and one frame slid);
#   - per frame: every frame copied (`--no-slide`), seconds over N;
#   - peak memory of that run (/usr/bin/time %M).
# Each figure should be flat in N (start-up and memory) or in N's per-frame share.
set -euo pipefail
export LC_ALL=C  # '.' decimal points in $EPOCHREALTIME and awk
root=$(cd "$(dirname "$0")/.." && pwd)
sizes="10000 100000 1000000"
frames=20
frames_big=4
runs=3
ict=1
peers=0
peers_only=0
peer_sizes=
peer_frames=1
peer_repeats=9
peer_e2e_frames=20
peer_e2e_frames_big=2
scale=
usage="usage: scripts/bench.sh [-s SIZES] [-f FRAMES] [-F FRAMES_BIG] [-r RUNS] [--no-ict] [--peers | --peers-only] [--peer-sizes SIZES] [--peer-frames N] [--peer-repeats N] [--peer-e2e-frames N] [--peer-e2e-frames-big N] [--scale [COUNTS]]"
while [ $# -gt 0 ]; do
  case $1 in
    -s) sizes=$2; shift 2 ;;
    -f) frames=$2; shift 2 ;;
    -F) frames_big=$2; shift 2 ;;
    -r) runs=$2; shift 2 ;;
    --no-ict) ict=0; shift ;;
    --peers) peers=1; shift ;;
    --peers-only) peers=1; peers_only=1; shift ;;
    --peer-sizes) peer_sizes=$2; shift 2 ;;
    --peer-frames) peer_frames=$2; shift 2 ;;
    --peer-repeats) peer_repeats=$2; shift 2 ;;
    --peer-e2e-frames) peer_e2e_frames=$2; shift 2 ;;
    --peer-e2e-frames-big) peer_e2e_frames_big=$2; shift 2 ;;
    --scale)
      scale="100 1000 10000"
      if [ $# -gt 1 ] && [[ $2 =~ ^[0-9\ ]+$ ]]; then scale=$2; shift; fi
      shift ;;
    *) echo "$usage" >&2; exit 2 ;;
  esac
done

# scale_bench: the --scale table (see above); prints it and exits.
scale_bench() {
  local bin=${SKINSLIDE:-}
  if [ -z "$bin" ]; then
    "$root/scripts/build.sh" --target skinslide >/dev/null
    bin=${SKINSLIDE_BUILD_DIR:-$root/build}/skinslide
  fi
  local work elbow=$root/data/elbow
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  # wall_peak OUT ARGS...: "seconds peak_kb" of `skinslide ARGS` appended to OUT
  wall_peak() {
    local out=$1
    shift
    rm -rf "$work/out"
    local t0=$EPOCHREALTIME
    /usr/bin/time -f "%M" -o "$work/time" "$bin" -q -j 1 "$@" -o "$work/out" 2>"$work/log" ||
      { echo "bench: skinslide $* failed: $(cat "$work/log")" >&2; exit 1; }
    echo "$(awk -v a="$t0" -v b="$EPOCHREALTIME" 'BEGIN {printf "%.4f", b - a}') $(cat "$work/time")" >>"$out"
  }
  echo "| frames | source | start-up s (--no-slide --frames 1) | --frames 1 s (set-up, one frame slid) | per frame ms (all copied) | peak MB (all copied) |"
  echo "|---|---|---|---|---|---|"
  for n in $scale; do
    mkdir -p "$work/f$n"
    for k in $(seq "$n"); do
      ln -s "$elbow/frames/elbow.000$(((k - 1) % 5 + 1)).obj" "$(printf '%s/f%d/elbow.%05d.obj' "$work" "$n" "$k")"
    done
    python3 - "$elbow/elbow.pc2" "$work/shot$n.pc2" "$n" <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
head = list(struct.unpack("<12siiffi", data[:32]))
size = head[2] * 12
samples = [data[32 + k * size:32 + (k + 1) * size] for k in range(head[5])]
n = int(sys.argv[3])
head[5] = n
with open(sys.argv[2], "wb") as f:
    f.write(struct.pack("<12siiffi", *head))
    for k in range(n):
        f.write(samples[k % len(samples)])
PY
    local patch=(--patch "$elbow/patch.txt" "$elbow/bind.obj")
    for source in obj pc2; do
      local frames=("$work/f$n"/*.obj)
      [ $source = pc2 ] && frames=("$work/shot$n.pc2")
      : >"$work/start" && : >"$work/one" && : >"$work/all"
      for r in $(seq "$runs"); do
        wall_peak "$work/start" --no-slide --frames 1 "${patch[@]}" "${frames[@]}"
        wall_peak "$work/one" --frames 1 "${patch[@]}" "${frames[@]}"
        wall_peak "$work/all" --no-slide "${patch[@]}" "${frames[@]}"
      done
      echo "| $n | $source | $(awk '{print $1}' "$work/start" | median) |" \
        "$(awk '{print $1}' "$work/one" | median) |" \
        "$(awk -v n="$n" '{printf "%.3f\n", 1000 * $1 / n}' "$work/all" | median) |" \
        "$(awk '{printf "%.1f\n", $2 / 1024}' "$work/all" | median) |"
    done
    rm -rf "$work/f$n" "$work/shot$n.pc2"
  done
  echo
  echo "$(nproc) cores: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); load after: $(cut -d' ' -f1-3 /proc/loadavg)"
  exit 0
}

median() { sort -g | awk '{v[NR] = $1} END {if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
[ -z "$scale" ] || scale_bench

"$root/scripts/build.sh" -DSKINSLIDE_BUILD_BENCH=ON >/dev/null
build=${SKINSLIDE_BUILD_DIR:-$root/build}
bin=$build/skinslide
gen=$build/tests/bench/skinslide_bench_case
stages=$build/tests/bench/skinslide_bench_stages
if [ -n "${BENCH_DIR:-}" ]; then
  work=$BENCH_DIR
  mkdir -p "$work"
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi

blender=${BLENDER:-blender}
if [ "$peers" = 1 ]; then
  [ -n "$peer_sizes" ] || peer_sizes="40000 100000 490000 1000000"
  if ! command -v "$blender" >/dev/null; then
    echo "bench: --peers needs Blender: scripts/deps.sh blender (large)" >&2
    if ! "$root/scripts/deps.sh" blender >"$work/apt-blender.log" 2>&1 ||
      ! command -v "$blender" >/dev/null; then
      tail -n 20 "$work/apt-blender.log" >&2
      echo "bench: could not install blender" >&2
      exit 1
    fi
  fi
fi


# bench NAME BIND PATCH FRAME...: appends "key value" lines to $work/NAME.result
bench() {
  local name=$1 bind=$2 patch=$3
  shift 3
  local res=$work/$name.result out=$work/$name.out
  : >"$res"
  echo "bench: $name ($# frames, $runs runs)" >&2
  # A frame's first pass faults in the pages of its work arrays; later frames reuse them (the
  # allocator keeps freed memory). With few frames the stage runs go over them three times, so
  # the medians are a shot's steady frames, as with 20 frames, not half first frames; the
  # set-up still runs once, cold, as in a farm task.
  local stage_frames=("$@")
  [ $# -lt 10 ] && stage_frames=("$@" "$@" "$@")
  for r in $(seq "$runs"); do
    "$stages" -o "$out/stages" "$bind" "$patch" "${stage_frames[@]}" >"$work/$name.stages.$r"
  done
  for key in $(awk '{print $1}' "$work/$name.stages.1"); do
    echo "$key $(cat "$work/$name".stages.* | awk -v k="$key" '$1 == k {print $2}' | median)" >>"$res"
  done
  # Both net solvers side by side (the runs above use the default, auto).
  for solver in cholesky multigrid; do
    for r in $(seq "$runs"); do
      "$stages" -s "$solver" -o "$out/stages" "$bind" "$patch" "${stage_frames[@]}" \
        >"$work/$name.$solver.$r"
    done
    for key in bind_setup frame_net cg_iterations; do
      echo "${solver}_$key $(cat "$work/$name.$solver".* | awk -v k="$key" '$1 == k {print $2}' | median)" >>"$res"
    done
  done
  # The command runs interleaved (slide -j1, -j2, floor -j1, -j2, then again): a shared machine's
  # speed drifts over minutes, and each run of a round sees the same drift. Wall time from the
  # shell's microsecond clock (time's %e has 10 ms steps: 7% of a 10k run).
  for mode in slide floor; do
    for j in 1 2; do : >"$work/$name.$mode.j$j"; done
  done
  for r in $(seq "$runs"); do
    for mode in slide floor; do
      for j in 1 2; do
        local flag=""
        [ "$mode" = floor ] && flag=--no-slide
        rm -rf "$out/cli"
        local t0=$EPOCHREALTIME
        /usr/bin/time -f "%M" -o "$work/time" "$bin" --method paper $flag -j "$j" --patch "$patch" "$bind" "$@" \
          -o "$out/cli" 2>"$work/log"
        local t1=$EPOCHREALTIME
        # The summary line "N frames slid in S s" times the frames alone, after the set-up.
        echo "$(awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.4f", b - a}') $(cat "$work/time")" \
          "$(sed -n 's/.* in \([0-9.]*\) s -> .*/\1/p' "$work/log" | tail -1)" \
          >>"$work/$name.$mode.j$j"
      done
    done
  done
  for mode in slide floor; do
    for j in 1 2; do
      echo "${mode}_seconds_j$j $(awk '{print $1}' "$work/$name.$mode.j$j" | median)" >>"$res"
      echo "${mode}_peak_kb_j$j $(awk '{print $2}' "$work/$name.$mode.j$j" | median)" >>"$res"
      echo "${mode}_frames_seconds_j$j $(awk '{print $3}' "$work/$name.$mode.j$j" | median)" >>"$res"
    done
  done
  echo "frames $#" >>"$res"
  rm -rf "$out"
}

# gen_case N: the synthetic case of N vertices in $work/caseN (kept when it is there); sets dir
gen_case() {
  local n=$1 f=$frames
  [ "$n" -ge 400000 ] && f=$frames_big
  dir=$work/case$n
  [ -f "$dir/bind.obj" ] && [ "$(ls "$dir/frames" | wc -l)" -eq "$f" ] || {
    rm -rf "$dir"
    "$gen" "$dir" "$n" "$f" >/dev/null
  }
}

# peer N: the elastic method on case N's first frame beside Corrective Smooth (below 1M
# vertices) -> $work/peerN.result
peer() {
  local n=$1 dir=$work/case$1 res=$work/peer$1.result
  local frame=$dir/frames/f.0001.obj
  : >"$res"
  if [ "$n" -lt 1000000 ]; then
    echo "bench: peers, synthetic $n: Corrective Smooth" >&2
    if ! "$blender" -b --factory-startup -noaudio --python-exit-code 1 -t 1 \
      --python "$root/scripts/corrective_smooth.py" -- time --bind "$dir/bind.obj" \
      --patch "$dir/patch.txt" --frame "$frame" --repeats "$peer_repeats" >"$work/peer$n.cs.log" 2>&1; then
      tail -n 20 "$work/peer$n.cs.log" >&2
      echo "bench: Corrective Smooth failed on synthetic $n" >&2
      exit 1
    fi
    grep '^cs_' "$work/peer$n.cs.log" | grep -v '^cs_info' >>"$res"
  fi
  [ "$peer_frames" -gt 0 ] || return 0  # Corrective Smooth alone
  echo "bench: peers, synthetic $n: skinslide elastic, stages x$peer_frames" >&2
  local fl=() k
  for k in $(seq "$peer_frames"); do fl+=("$frame"); done
  "$stages" -m elastic -o "$work/peer_out" "$dir/bind.obj" "$dir/patch.txt" "${fl[@]}" \
    >"$work/peer$n.stages"
  "$stages" -m paper -b -o "$work/peer_out" "$dir/bind.obj" "$dir/patch.txt" >"$work/peer$n.paper"
  rm -rf "$work/peer_out"
  for k in relax slide_frame elastic_iterations patch_vertices mesh_vertices bind_setup; do
    echo "elastic_${k#elastic_} $(awk -v k="$k" '$1 == k {print $2}' "$work/peer$n.stages")" >>"$res"
  done
  echo "paper_bind_setup $(awk '$1 == "bind_setup" {print $2}' "$work/peer$n.paper")" >>"$res"
  # End to end, the command's default (elastic): bind + E frames with -j1 against the I/O floor
  # (--no-slide) of the same command; the peak memory also with -j2 on the same frames.
  local e=$peer_e2e_frames
  [ "$n" -ge 400000 ] && e=$peer_e2e_frames_big
  local frames=("$dir"/frames/*.obj)
  frames=("${frames[@]:0:$e}")
  echo "bench: peers, synthetic $n: skinslide end to end, ${#frames[@]} frames" >&2
  for mode in slide floor slide2; do
    local flag="-j 1"
    [ "$mode" = floor ] && flag="-j 1 --no-slide"
    [ "$mode" = slide2 ] && flag="-j 2"
    rm -rf "$work/peer_cli"
    local t0=$EPOCHREALTIME
    /usr/bin/time -f "%M" -o "$work/time" "$bin" $flag --patch "$dir/patch.txt" "$dir/bind.obj" \
      "${frames[@]}" -o "$work/peer_cli" 2>"$work/log"
    local t1=$EPOCHREALTIME
    echo "e2e_${mode}_seconds $(awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.4f", b - a}')" >>"$res"
    echo "e2e_${mode}_peak_kb $(cat "$work/time")" >>"$res"
  done
  rm -rf "$work/peer_cli"
  echo "e2e_frames ${#frames[@]}" >>"$res"
}

names=()
[ "$peers_only" = 1 ] && sizes=
for n in $sizes; do
  gen_case "$n"
  bench "synthetic $n" "$dir/bind.obj" "$dir/patch.txt" "$dir"/frames/*.obj
  names+=("synthetic $n")
done
ictdir=$root/../shared/data/obj/ict-facekit
if [ "$ict" = 1 ] && [ "$peers_only" = 0 ] && [ -f "$ictdir/generic_neutral_mesh.obj" ]; then
  echo "0-9229  # the face with mouth and eye holes" >"$work/ict_patch.txt"
  bench "ICT face" "$ictdir/generic_neutral_mesh.obj" "$work/ict_patch.txt" \
    "$ictdir"/{jawOpen,mouthSmile_L,eyeBlink_L,browInnerUp_L}.obj
  names+=("ICT face")
fi

peer_names=()
if [ "$peers" = 1 ]; then
  for n in $peer_sizes; do
    gen_case "$n"
    peer "$n"
    peer_names+=("$n")
  done
fi

echo
echo "$(nproc) cores: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); load before: $(cut -d' ' -f1-3 /proc/loadavg)"
[ ${#names[@]} -eq 0 ] || python3 - "$work" "${names[@]}" <<'EOF'
import sys
work, names = sys.argv[1], sys.argv[2:]
rows = []
for name in names:
    r = {}
    for line in open(f"{work}/{name}.result"):
        k, v = line.split()
        r[k] = float(v)
    rows.append((name, r))

def ms(x):
    return f"{x:.0f}" if x >= 100 else f"{x:.1f}" if x >= 1 else f"{x:.2f}"

print("\n| case | mesh / patch vertices | bind read + set-up ms | read | frame net | locate | transfer | write | compute (net+locate+transfer) | fps -j1 | fps -j2 | -j2/-j1 (frames alone) | floor fps -j1 | floor fps -j2 | end to end / floor | peak MB -j1 / -j2 |")
print("|" + "---|" * 16)
for name, r in rows:
    f = r["frames"]
    floor = r["floor_seconds_j1"] * 1000 / f  # ms per frame, one thread
    x = lambda v: f"{ms(v)} ({v / floor:.2f}x)"
    compute = r["frame_net"] + r["locate"] + r.get("id_image", 0) + r["transfer"]
    fps1 = f / r["slide_seconds_j1"]
    fps2 = f / r["slide_seconds_j2"]
    print(f"| {name} | {r['mesh_vertices']:.0f} / {r['patch_vertices']:.0f} | {ms(r['bind_read'])} + {ms(r['bind_setup'])} "
          f"| {x(r['read'])} | {x(r['frame_net'])} | {x(r['locate'])} | {x(r['transfer'])} | {x(r['write'])} | {x(compute)} "
          f"| {fps1:.2f} | {fps2:.2f} | {fps2 / fps1:.2f} ({r['slide_frames_seconds_j1'] / r['slide_frames_seconds_j2']:.2f}) "
          f"| {f / r['floor_seconds_j1']:.2f} | {f / r['floor_seconds_j2']:.2f} "
          f"| {r['slide_seconds_j1'] / r['floor_seconds_j1']:.2f}x (-j1), {r['slide_seconds_j2'] / r['floor_seconds_j2']:.2f}x (-j2) "
          f"| {r['slide_peak_kb_j1'] / 1024:.0f} / {r['slide_peak_kb_j2'] / 1024:.0f} |")
print("\n| case | patch vertices | set-up ms: cholesky / multigrid | frame net ms: cholesky / multigrid (iterations) |")
print("|---|---|---|---|")
for name, r in rows:
    print(f"| {name} | {r['patch_vertices']:.0f} | {ms(r['cholesky_bind_setup'])} / {ms(r['multigrid_bind_setup'])} "
          f"| {ms(r['cholesky_frame_net'])} / {ms(r['multigrid_frame_net'])} ({r['multigrid_cg_iterations']:.0f}) |")
print("\nStage times: median CPU ms of one thread per frame; (Nx) = N times the I/O floor's time per "
      "frame (--no-slide, -j1). fps: frames/second of the whole command (bind set-up included), wall clock; "
      "(frames alone): the speed-up of the frame loop, after the set-up.")
EOF
if [ "$peers" = 1 ]; then
  echo
  echo "Peer: $("$blender" -b --factory-startup --version 2>/dev/null | grep -m1 '^Blender' || echo 'Blender ?'), Corrective Smooth, 10 iterations, -t 1"
  python3 - "$work" "${peer_names[@]}" <<'EOF'
import sys
work, names = sys.argv[1], sys.argv[2:]

def ms(x):
    return f"{x:.0f}" if x >= 100 else f"{x:.1f}" if x >= 1 else f"{x:.2f}"

print("\n| case | mesh / free vertices | Corrective Smooth ms: frame eval (overhead) | modifier | cold (first eval) "
      "| skinslide elastic ms: relax (steps) | slide_frame | elastic relax / CS modifier "
      "| bind set-up ms: elastic / paper | end to end s/frame -j1 (I/O floor) | peak MB -j1 / -j2 |")
print("|" + "---|" * 11)
for n in names:
    r = {}
    for line in open(f"{work}/peer{n}.result"):
        k, v = line.split()
        r[k] = float(v)
    cs = (f"| {ms(r['cs_frame_ms'])} ({ms(r['cs_overhead_ms'])}) | {ms(r['cs_modifier_ms'])} | {ms(r['cs_cold_ms'])} "
          if "cs_modifier_ms" in r else "| - | - | - ")
    if "elastic_relax" not in r:
        el = "| n/a | n/a | n/a | n/a | n/a | n/a |"
    else:
        ratio = f"{r['elastic_relax'] / r['cs_modifier_ms']:.0f}x" if "cs_modifier_ms" in r else "-"
        f = r["e2e_frames"]
        e2e = r["e2e_slide_seconds"] / f
        floor = r["e2e_floor_seconds"] / f
        el = (f"| {ms(r['elastic_relax'])} ({r['elastic_iterations']:.0f}) | {ms(r['elastic_slide_frame'])} | {ratio} "
              f"| {ms(r['elastic_bind_setup'])} / {ms(r['paper_bind_setup'])} ({r['elastic_bind_setup'] / r['paper_bind_setup']:.1f}x) "
              f"| {e2e:.3g} ({floor:.3g}; {e2e / floor:.0f}x, {f:.0f} frames) "
              f"| {r['e2e_slide_peak_kb'] / 1024:.0f} / {r['e2e_slide2_peak_kb'] / 1024:.0f} |")
    vertices = r.get("cs_vertices", r.get("elastic_mesh_vertices", 0))
    free = r.get("cs_free_vertices", r.get("elastic_patch_vertices", 0))
    print(f"| synthetic {n} | {vertices:.0f} / {free:.0f} " + cs + el)
print("\nCPU ms per frame, one thread, the case's first frame. Corrective Smooth (below 1M vertices): medians "
      "of warm scene evaluations (its rest cache kept, as in playback); modifier = frame eval minus the same "
      "evaluation with the modifier off (overhead: shape key mix, mesh copy). skinslide: the elastic method's "
      "relax stage (bench_stages -m elastic), slide_frame = relax + the transfer of its result; bind set-up of "
      "both methods (bench_stages -b). End to end: wall seconds of the command (bind + frames) per frame, -j1, "
      "against the same command with --no-slide (the I/O floor); peak resident memory of the command.")
EOF
fi
