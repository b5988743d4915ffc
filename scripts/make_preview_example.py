#!/usr/bin/env python3
"""Writes data/preview_example.png, the preview shown in README "Dumps".

A 12 x 12 quad grid (2 x 2 units in the xy-plane) is bent by 110 degrees about the line x = 1
by two-bone linear blend skinning (bone-2 weight = smoothstep over x in [0.7, 1.3]), which
shortens the bars across the bend, and a bulge (a Gaussian bump of height 0.5 at (0.6, 1.3))
stretches the bars around it; the whole grid is the patch. skinslide slides the frame with
--method paper (the nets this picture explains) and draws the preview at 512 pixels: the frame
net (orange) swells under the bulge and shrinks at the bend.

    python3 scripts/make_preview_example.py path/to/skinslide data/preview_example.png

Python 3 standard library only; the same bytes every run.
"""
import math
import pathlib
import shutil
import subprocess
import sys
import tempfile

N = 12          # quads along each side
SIZE = 2.0      # side of the grid, mesh units
ANGLE = 110.0   # bend, degrees
PREVIEW = 512   # preview side, pixels


def smoothstep(a, b, x):
    t = min(1.0, max(0.0, (x - a) / (b - a)))
    return t * t * (3 - 2 * t)


def grid():
    return [(SIZE * i / N, SIZE * j / N, 0.0) for j in range(N + 1) for i in range(N + 1)]


def bend(p):
    x, y, z = p
    c, s = math.cos(math.radians(ANGLE)), math.sin(math.radians(ANGLE))
    # Bone 2 rotates about the line x = 1, z = 0 (parallel to y), lifting the right half.
    rx = 1.0 + (x - 1.0) * c - z * s
    rz = (x - 1.0) * s + z * c
    w = smoothstep(0.7, 1.3, x)
    bump = 0.5 * math.exp(-((x - 0.6) ** 2 + (y - 1.3) ** 2) / 0.08)
    return ((1 - w) * x + w * rx, y, (1 - w) * z + w * rz + bump)


def write_obj(path, points):
    lines = ["# skinslide preview example: bent grid", "o grid"]
    lines += ["v %.9f %.9f %.9f" % p for p in points]
    for j in range(N):
        for i in range(N):
            a = j * (N + 1) + i + 1
            lines.append("f %d %d %d %d" % (a, a + 1, a + N + 2, a + N + 1))
    path.write_text("\n".join(lines) + "\n")


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: make_preview_example.py SKINSLIDE OUT.png")
    skinslide, out = sys.argv[1], pathlib.Path(sys.argv[2])
    with tempfile.TemporaryDirectory() as tmp:
        d = pathlib.Path(tmp)
        bind = grid()
        write_obj(d / "bind.obj", bind)
        (d / "frames").mkdir()
        write_obj(d / "frames" / "bent.0001.obj", [bend(p) for p in bind])
        (d / "patch.txt").write_text("0-%d\n" % (N * N - 1))
        subprocess.run([skinslide, "-q", "--method", "paper", "--patch", str(d / "patch.txt"),
                        str(d / "bind.obj"), str(d / "frames" / "bent.0001.obj"), "-o", str(d / "slid"),
                        "--preview", str(d / "preview"), "--preview-size", str(PREVIEW)],
                       check=True)
        shutil.copyfile(d / "preview" / "bent.0001.patch000.png", out)
    print(out)


if __name__ == "__main__":
    main()
