#!/usr/bin/env bash
# Benchmarks skinslide: synthetic cases generated on the fly (a curved, unevenly stretched
# surface with three holes, bent at a joint by two-bone skinning; tests/bench/bench_case.cpp)
# and the ICT face of ../shared/data (neutral = bind, four expressions = frames).
#
#   scripts/bench.sh [-s "10000 100000 1000000"] [-f FRAMES] [-F FRAMES_BIG] [-r RUNS] [--no-ict]
#   (FRAMES frames per case, default 20; FRAMES_BIG, default 4, from 400k vertices on)
#
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
set -euo pipefail
export LC_ALL=C  # '.' decimal points in $EPOCHREALTIME and awk
root=$(cd "$(dirname "$0")/.." && pwd)
sizes="10000 100000 1000000"
frames=20
frames_big=4
runs=3
ict=1
while [ $# -gt 0 ]; do
  case $1 in
    -s) sizes=$2; shift 2 ;;
    -f) frames=$2; shift 2 ;;
    -F) frames_big=$2; shift 2 ;;
    -r) runs=$2; shift 2 ;;
    --no-ict) ict=0; shift ;;
    *) echo "usage: scripts/bench.sh [-s SIZES] [-f FRAMES] [-F FRAMES_BIG] [-r RUNS] [--no-ict]" >&2; exit 2 ;;
  esac
done

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

median() { sort -g | awk '{v[NR] = $1} END {if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

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
        /usr/bin/time -f "%M" -o "$work/time" "$bin" $flag -j "$j" --patch "$patch" "$bind" "$@" \
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

names=()
for n in $sizes; do
  f=$frames
  [ "$n" -ge 400000 ] && f=$frames_big
  dir=$work/case$n
  [ -f "$dir/bind.obj" ] && [ "$(ls "$dir/frames" | wc -l)" -eq "$f" ] || {
    rm -rf "$dir"
    "$gen" "$dir" "$n" "$f" >/dev/null
  }
  bench "synthetic $n" "$dir/bind.obj" "$dir/patch.txt" "$dir"/frames/*.obj
  names+=("synthetic $n")
done
ictdir=$root/../shared/data/obj/ict-facekit
if [ "$ict" = 1 ] && [ -f "$ictdir/generic_neutral_mesh.obj" ]; then
  echo "0-9229  # the face with mouth and eye holes" >"$work/ict_patch.txt"
  bench "ICT face" "$ictdir/generic_neutral_mesh.obj" "$work/ict_patch.txt" \
    "$ictdir"/{jawOpen,mouthSmile_L,eyeBlink_L,browInnerUp_L}.obj
  names+=("ICT face")
fi

echo
echo "$(nproc) cores: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); load before: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$work" "${names[@]}" <<'EOF'
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
