#!/usr/bin/python3
"""Writes data/before_after.png, the picture at the top of README.md.

The ICT-FaceKit face (faces 0-9229 of generic_neutral_mesh.obj: the face with its mouth and eye
holes) is the patch; the jawOpen shape is the frame. skinslide slides it (elastic, `--solver
search`: an expression is a separate pose),
and both the frame as the deformer left it and the slid frame are drawn side by side, from the
front (orthographic, z-buffered, flat-shaded), each face coloured by how much its edges changed
length against the bind: the mean of log(L / L_bind) over the face's edges, white = as in the
bind, red = stretched, blue = squashed (the colour bar spans -30% .. +30%). The rest of the
head is drawn grey. The numbers under each view are the edge-length spread over the patch,
std of log(L / L_bind) over its edges, the figure scripts/quality.sh compares.

    /usr/bin/python3 scripts/make_before_after.py build/skinslide [OUT.png] [ICT_DIR]

OUT.png defaults to data/before_after.png, ICT_DIR to SHARED/data/obj/ict-facekit, SHARED being
$SKINSLIDE_SHARED_DIR or else ../shared beside this repository (as for the tests).
Needs numpy (Debian python3-numpy, which scripts/deps.sh installs); the PNG is written with
zlib, the text with a built-in 5 x 7 pixel font. The same inputs give the same bytes.
"""
import os
import pathlib
import struct
import subprocess
import sys
import tempfile
import zlib

import numpy as np

PATCH_FACES = 9230          # faces 0..9229
EXPRESSION = "jawOpen"
PANEL = 480                 # side of each view, pixels
SS = 3                      # supersampling per axis
RANGE = np.log(1.3)         # colour bar: -30% .. +30% edge length change
YAW = np.radians(-28.0)     # turn the head a little, so the jaw's depth reads
LIGHT = np.array([-0.35, 0.45, 1.0])

# ------------------------------------------------------------------------------- meshes


def read_obj(path):
    """v and f lines: positions (n, 3) and faces (lists of 0-based vertex ids)."""
    verts, faces = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                verts.append([float(t) for t in line.split()[1:4]])
            elif line.startswith("f "):
                faces.append([int(t.split("/")[0]) - 1 for t in line.split()[1:]])
    return np.array(verts), faces


def face_stretch(pos, bind, faces):
    """Per face: mean of log(L / L_bind) over its edges. Also every patch edge's log ratio."""
    per_face, edges = [], {}
    for f in faces:
        logs = []
        for a, b in zip(f, f[1:] + f[:1]):
            lb = np.linalg.norm(bind[a] - bind[b])
            lf = np.linalg.norm(pos[a] - pos[b])
            r = np.log(lf / lb) if lb > 0 and lf > 0 else 0.0
            logs.append(r)
            edges[(min(a, b), max(a, b))] = r
        per_face.append(np.mean(logs))
    return np.array(per_face), np.array(list(edges.values()))


# ------------------------------------------------------------------------------ drawing


def colour(t):
    """Diverging map: -1 blue, 0 near white, +1 red (RGB in 0..1)."""
    t = np.clip(t, -1, 1)[:, None]
    white = np.array([0.97, 0.96, 0.94])
    blue = np.array([0.16, 0.35, 0.80])
    red = np.array([0.80, 0.10, 0.10])
    return np.where(t < 0, white + (blue - white) * (-t), white + (red - white) * t)


def triangles(faces):
    tri, owner = [], []
    for i, f in enumerate(faces):
        for k in range(1, len(f) - 1):
            tri.append((f[0], f[k], f[k + 1]))
            owner.append(i)
    return np.array(tri), np.array(owner)


def rasterise(img, depth, p2, z, tri, rgb):
    """Fills triangles (screen positions p2, depth z: larger is nearer) with a z-buffer."""
    h, w = depth.shape
    for (a, b, c), col in zip(tri, rgb):
        xa, ya = p2[a]
        xb, yb = p2[b]
        xc, yc = p2[c]
        x0, x1 = int(max(0, np.floor(min(xa, xb, xc)))), int(min(w - 1, np.ceil(max(xa, xb, xc))))
        y0, y1 = int(max(0, np.floor(min(ya, yb, yc)))), int(min(h - 1, np.ceil(max(ya, yb, yc))))
        if x1 < x0 or y1 < y0:
            continue
        area = (xb - xa) * (yc - ya) - (xc - xa) * (yb - ya)
        if abs(area) < 1e-12:
            continue
        xs, ys = np.meshgrid(np.arange(x0, x1 + 1) + 0.5, np.arange(y0, y1 + 1) + 0.5)
        l0 = ((xb - xs) * (yc - ys) - (xc - xs) * (yb - ys)) / area
        l1 = ((xc - xs) * (ya - ys) - (xa - xs) * (yc - ys)) / area
        l2 = 1 - l0 - l1
        inside = (l0 >= 0) & (l1 >= 0) & (l2 >= 0)
        zz = l0 * z[a] + l1 * z[b] + l2 * z[c]
        win = inside & (zz > depth[y0:y1 + 1, x0:x1 + 1])
        depth[y0:y1 + 1, x0:x1 + 1][win] = zz[win]
        img[y0:y1 + 1, x0:x1 + 1][win] = col


def render(pos, faces, face_rgb, frame_box):
    """One view: orthographic from the front (+z), head turned by YAW, flat Lambert shading."""
    c, s = np.cos(YAW), np.sin(YAW)
    rot = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    p = pos @ rot.T
    (lo, hi) = frame_box
    n = PANEL * SS
    scale = 0.94 * n / max(hi[0] - lo[0], hi[1] - lo[1])
    centre = (lo + hi) / 2
    p2 = np.empty((len(p), 2))
    p2[:, 0] = (p[:, 0] - centre[0]) * scale + n / 2
    p2[:, 1] = n / 2 - (p[:, 1] - centre[1]) * scale
    tri, owner = triangles(faces)
    nrm = np.cross(p[tri[:, 1]] - p[tri[:, 0]], p[tri[:, 2]] - p[tri[:, 0]])
    nrm /= np.maximum(np.linalg.norm(nrm, axis=1), 1e-30)[:, None]
    keep = nrm[:, 2] > 0  # front-facing only (the head is closed enough from the front)
    light = LIGHT / np.linalg.norm(LIGHT)
    shade = 0.45 + 0.55 * np.clip(nrm @ light, 0, 1)
    rgb = face_rgb[owner] * shade[:, None]
    img = np.ones((n, n, 3))
    depth = np.full((n, n), -np.inf)
    rasterise(img, depth, p2, p[:, 2], tri[keep], rgb[keep])
    return img.reshape(PANEL, SS, PANEL, SS, 3).mean(axis=(1, 3))


def view_box(pos, patch_vertices):
    c, s = np.cos(YAW), np.sin(YAW)
    rot = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    p = pos[patch_vertices] @ rot.T
    lo, hi = p.min(axis=0), p.max(axis=0)
    pad = 0.04 * (hi - lo)
    return lo - pad, hi + pad


# --------------------------------------------------------------------------------- text

FONT_ROWS = {
    "A": ".###. #...# #...# ##### #...# #...# #...#",
    "B": "####. #...# #...# ####. #...# #...# ####.",
    "C": ".###. #...# #.... #.... #.... #...# .###.",
    "D": "####. #...# #...# #...# #...# #...# ####.",
    "E": "##### #.... #.... ####. #.... #.... #####",
    "F": "##### #.... #.... ####. #.... #.... #....",
    "G": ".###. #...# #.... #.### #...# #...# .####",
    "H": "#...# #...# #...# ##### #...# #...# #...#",
    "I": ".###. ..#.. ..#.. ..#.. ..#.. ..#.. .###.",
    "J": "..### ...#. ...#. ...#. ...#. #..#. .##..",
    "K": "#...# #..#. #.#.. ##... #.#.. #..#. #...#",
    "L": "#.... #.... #.... #.... #.... #.... #####",
    "M": "#...# ##.## #.#.# #.#.# #...# #...# #...#",
    "N": "#...# #...# ##..# #.#.# #..## #...# #...#",
    "O": ".###. #...# #...# #...# #...# #...# .###.",
    "P": "####. #...# #...# ####. #.... #.... #....",
    "Q": ".###. #...# #...# #...# #.#.# #..#. .##.#",
    "R": "####. #...# #...# ####. #.#.. #..#. #...#",
    "S": ".#### #.... #.... .###. ....# ....# ####.",
    "T": "##### ..#.. ..#.. ..#.. ..#.. ..#.. ..#..",
    "U": "#...# #...# #...# #...# #...# #...# .###.",
    "V": "#...# #...# #...# #...# #...# .#.#. ..#..",
    "W": "#...# #...# #...# #.#.# #.#.# #.#.# .#.#.",
    "X": "#...# #...# .#.#. ..#.. .#.#. #...# #...#",
    "Y": "#...# #...# .#.#. ..#.. ..#.. ..#.. ..#..",
    "Z": "##### ....# ...#. ..#.. .#... #.... #####",
    "0": ".###. #...# #..## #.#.# ##..# #...# .###.",
    "1": "..#.. .##.. ..#.. ..#.. ..#.. ..#.. .###.",
    "2": ".###. #...# ....# ...#. ..#.. .#... #####",
    "3": "##### ...#. ..#.. ...#. ....# #...# .###.",
    "4": "...#. ..##. .#.#. #..#. ##### ...#. ...#.",
    "5": "##### #.... ####. ....# ....# #...# .###.",
    "6": "..##. .#... #.... ####. #...# #...# .###.",
    "7": "##### ....# ...#. ..#.. .#... .#... .#...",
    "8": ".###. #...# #...# .###. #...# #...# .###.",
    "9": ".###. #...# #...# .#### ....# ...#. .##..",
    "-": "..... ..... ..... ##### ..... ..... .....",
    "+": "..... ..#.. ..#.. ##### ..#.. ..#.. .....",
    "%": "##... ##..# ...#. ..#.. .#... #..## ...##",
    ":": "..... .##.. .##.. ..... .##.. .##.. .....",
    ".": "..... ..... ..... ..... ..... .##.. .##..",
    ",": "..... ..... ..... ..... .##.. ..#.. .#...",
    "(": "...#. ..#.. .#... .#... .#... ..#.. ...#.",
    ")": ".#... ..#.. ...#. ...#. ...#. ..#.. .#...",
    "/": "..... ....# ...#. ..#.. .#... #.... .....",
    "=": "..... ..... ##### ..... ##### ..... .....",
    " ": "..... ..... ..... ..... ..... ..... .....",
}


def text(img, x, y, s, scale=2, rgb=(0.1, 0.1, 0.1), centre=False):
    """Draws s (upper case) with its top left at (x, y), or centred on x."""
    s = s.upper()
    width = (6 * len(s) - 1) * scale
    if centre:
        x -= width // 2
    for k, ch in enumerate(s):
        rows = FONT_ROWS[ch].split()
        for r, row in enumerate(rows):
            for cidx, bit in enumerate(row):
                if bit == "#":
                    x0 = x + (6 * k + cidx) * scale
                    y0 = y + r * scale
                    img[y0:y0 + scale, x0:x0 + scale] = rgb


# ---------------------------------------------------------------------------------- PNG


def write_png(path, img):
    """8-bit RGB PNG through zlib (filter: none)."""
    a = np.clip(np.round(img * 255), 0, 255).astype(np.uint8)
    h, w, _ = a.shape
    raw = b"".join(b"\x00" + a[y].tobytes() for y in range(h))

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
           chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    pathlib.Path(path).write_bytes(png)


# --------------------------------------------------------------------------------- main


def main():
    if not 2 <= len(sys.argv) <= 4:
        sys.exit("usage: make_before_after.py SKINSLIDE [OUT.png] [ICT_DIR]")
    skinslide = sys.argv[1]
    root = pathlib.Path(__file__).resolve().parent.parent
    out = sys.argv[2] if len(sys.argv) > 2 else str(root / "data" / "before_after.png")
    shared = pathlib.Path(os.environ.get("SKINSLIDE_SHARED_DIR") or root.parent / "shared")
    ict = pathlib.Path(sys.argv[3]) if len(sys.argv) > 3 else shared / "data/obj/ict-facekit"
    with tempfile.TemporaryDirectory() as tmp:
        d = pathlib.Path(tmp)
        (d / "patch.txt").write_text("0-%d\n" % (PATCH_FACES - 1))
        subprocess.run([skinslide, "-q", "--solver", "search", "--patch", str(d / "patch.txt"),
                        str(ict / "generic_neutral_mesh.obj"), str(ict / (EXPRESSION + ".obj")),
                        "-o", str(d / "slid")], check=True)
        bind, faces = read_obj(ict / "generic_neutral_mesh.obj")
        frame, _ = read_obj(ict / (EXPRESSION + ".obj"))
        slid, _ = read_obj(d / "slid" / (EXPRESSION + ".obj"))

    patch, rest = faces[:PATCH_FACES], faces[PATCH_FACES:]
    patch_vertices = sorted({v for f in patch for v in f})
    box = view_box(frame, patch_vertices)
    grey = np.array([0.72, 0.72, 0.72])
    views, spreads = [], []
    for pos in (frame, slid):
        stretch, edge_logs = face_stretch(pos, bind, patch)
        spreads.append(np.std(edge_logs))
        face_rgb = np.vstack([colour(stretch / RANGE), np.tile(grey, (len(rest), 1))])
        views.append(render(pos, patch + rest, face_rgb, box))

    top, bottom, gap = 44, 92, 16
    width = 2 * PANEL + 3 * gap
    img = np.ones((top + PANEL + bottom, width, 3))
    for k, v in enumerate(views):
        x = gap + k * (PANEL + gap)
        img[top:top + PANEL, x:x + PANEL] = v
    centres = [gap + PANEL // 2, 2 * gap + PANEL + PANEL // 2]
    text(img, centres[0], 14, "BEFORE: JAWOPEN, DEFORMER ONLY", centre=True)
    text(img, centres[1], 14, "AFTER: + SKINSLIDE (ELASTIC)", centre=True)
    for c, sp in zip(centres, spreads):
        text(img, c, top + PANEL + 6, "EDGE STRETCH SPREAD %.3f" % sp, centre=True)
    # Colour bar: -30% .. +30% edge length against the bind.
    bar_w, bar_h = 360, 12
    bx, by = (width - bar_w) // 2, top + PANEL + 36
    t = (np.arange(bar_w) + 0.5) / bar_w * 2 - 1
    img[by:by + bar_h, bx:bx + bar_w] = colour(t)[None, :, :]
    img[by - 1, bx - 1:bx + bar_w + 1] = img[by + bar_h, bx - 1:bx + bar_w + 1] = 0.4
    img[by - 1:by + bar_h + 1, bx - 1] = img[by - 1:by + bar_h + 1, bx + bar_w] = 0.4
    text(img, bx - 12 - (6 * 13 - 1) * 2, by - 1, "SQUASHED -30%")
    text(img, bx + bar_w + 12, by - 1, "+30% STRETCHED")
    text(img, width // 2, by + bar_h + 8, "EDGE LENGTH VS BIND (GREY: NOT IN THE PATCH)",
         centre=True)
    write_png(out, img)
    print("%s: spread frame %.4f, slid %.4f" % (out, spreads[0], spreads[1]))


if __name__ == "__main__":
    main()
