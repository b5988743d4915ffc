#!/usr/bin/python3
"""Measures every --density x --holes setting of --method paper on the sample cases and the ICT face.

    scripts/measure_modes.py SKINSLIDE [--quick]

For each case, mode and frame it runs skinslide, then ../shared/reference/metrics.py, and prints a
markdown table per case and a summary: flips (slid triangles whose normal turns against the
frame's), on-surface distance, and how the edge-length spread changes: edge_logstd_ratio =
std(log L_slid/L_bind) / std(log L_frame/L_bind) (< 1: sliding evened out the stretch) and
edge_restoration = mean|L_slid/L_bind - 1| / mean|L_frame/L_bind - 1|. Needs python3-numpy and
python3-scipy (for metrics.py).
"""
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
SHARED = os.path.normpath(os.path.join(ROOT, "..", "shared"))
METRICS = os.path.join(SHARED, "reference", "metrics.py")
ICT = os.path.join(SHARED, "data", "obj", "ict-facekit")


def cases(tmp):
    ict_patch = os.path.join(tmp, "ict_face.txt")
    with open(ict_patch, "w") as fh:
        fh.write("\n".join(str(i) for i in range(9230)) + "\n")
    out = []
    for name in ("elbow", "face"):
        d = os.path.join(ROOT, "data", name)
        frames = sorted(os.path.join(d, "frames", f) for f in os.listdir(os.path.join(d, "frames")))
        out.append((name, os.path.join(d, "bind.obj"), os.path.join(d, "patch_plain.txt"), frames))
    out.append(("ict-face", os.path.join(ICT, "generic_neutral_mesh.obj"), ict_patch,
                [os.path.join(ICT, n + ".obj") for n in ("jawOpen", "mouthSmile_L", "eyeBlink_L",
                                                         "browInnerUp_L")]))
    return out


def main(argv):
    binary = argv[0]
    tmp = tempfile.mkdtemp(prefix="skinslide_modes_")
    summary = []
    for name, bind, patch, frames in cases(tmp):
        print("\n### %s\n" % name)
        print("| density | holes | frame | flips | on-surface max/diag | edge logstd ratio | edge restoration |")
        print("|---|---|---|---|---|---|---|")
        for density in ("paper", "inverse", "uniform"):
            for holes in ("free", "fill"):
                out = os.path.join(tmp, name, density + "_" + holes)
                subprocess.run([binary, "-q", "--method", "paper", "--density", density, "--holes", holes, "--patch", patch,
                                bind] + frames + ["-o", out], check=True)
                flips, ratios, restor = 0, [], []
                for f in frames:
                    m = json.loads(subprocess.run(
                        ["/usr/bin/python3", METRICS, bind, patch, f, os.path.join(out, os.path.basename(f))],
                        check=True, capture_output=True, text=True).stdout)
                    flips += m["flips"]
                    if m["edge_logstd_ratio"] is not None:
                        ratios.append(m["edge_logstd_ratio"])
                    if m["edge_restoration"] is not None:
                        restor.append(m["edge_restoration"])
                    print("| %s | %s | %s | %d | %.2g | %s | %s |" % (
                        density, holes, os.path.basename(f), m["flips"], m["on_surface_max_rel"] or 0,
                        "%.3f" % m["edge_logstd_ratio"] if m["edge_logstd_ratio"] is not None else "-",
                        "%.3f" % m["edge_restoration"] if m["edge_restoration"] is not None else "-"))
                summary.append((name, density, holes, flips, max(ratios) if ratios else float("nan"),
                                sum(ratios) / len(ratios) if ratios else float("nan")))
    print("\n### Summary (all frames of a case)\n")
    print("| case | density | holes | flips | worst edge logstd ratio | mean edge logstd ratio |")
    print("|---|---|---|---|---|---|")
    for row in summary:
        print("| %s | %s | %s | %d | %.3f | %.3f |" % row)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
