#!/usr/bin/python3
"""Pictures of slid stress frames, to look at them as a TD would.

    make_stress_views.py CASE_DIR FRAME OUT.png [METHOD ...]

CASE_DIR is one case's folder as `scripts/stress.sh --keep DIR` leaves it (DIR/CASE: bind.obj,
patch.txt, frames/, one folder of slid frames per method). For FRAME (a file name in frames/)
draws the frame as the deformer left it and each METHOD's slid frame (default: elastic
corrective-smooth), side by side, twice: seen from either side of the patch. The view looks
along the patch's middle principal axis (a band round a limb is seen from the side), orthographic,
z-buffered, flat-shaded, the rest of the mesh grey. Faces are coloured as in
scripts/make_before_after.py (whose drawing code this uses): the mean of log(L / L_bind) over
the face's edges, white = as in the bind, red = stretched, blue = squashed, the colour bar
+-30%; a face turned against the frame's is drawn black. Under each view: the edge-length spread
(std of log(L / L_bind) over patch edges) and the flipped faces.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_before_after as mb  # noqa: E402

PANEL = 380


def read_patch_ids(path):
    ids = []
    with open(path) as fh:
        for line in fh:
            ids.extend(int(t) for t in line.split("#")[0].split())
    return sorted(set(ids))


def normals(P, faces):
    tri, owner = mb.triangles(faces)
    n = np.cross(P[tri[:, 1]] - P[tri[:, 0]], P[tri[:, 2]] - P[tri[:, 0]])
    out = np.zeros((len(faces), 3))
    np.add.at(out, owner, n)
    return out


def render(P, faces, face_rgb, R, box):
    p = P @ R.T
    lo, hi = box
    n = PANEL * mb.SS
    scale = 0.94 * n / max(hi[0] - lo[0], hi[1] - lo[1])
    c = (lo + hi) / 2
    p2 = np.empty((len(p), 2))
    p2[:, 0] = (p[:, 0] - c[0]) * scale + n / 2
    p2[:, 1] = n / 2 - (p[:, 1] - c[1]) * scale
    tri, owner = mb.triangles(faces)
    nrm = np.cross(p[tri[:, 1]] - p[tri[:, 0]], p[tri[:, 2]] - p[tri[:, 0]])
    nrm /= np.maximum(np.linalg.norm(nrm, axis=1), 1e-30)[:, None]
    keep = nrm[:, 2] > 0
    light = mb.LIGHT / np.linalg.norm(mb.LIGHT)
    shade = 0.45 + 0.55 * np.clip(nrm @ light, 0, 1)
    rgb = face_rgb[owner] * shade[:, None]
    # only what is near the patch: triangles with a corner inside the box (padded)
    inside = np.all((p[:, :2] >= lo[:2] - 0.2 * (hi[:2] - lo[:2])) &
                    (p[:, :2] <= hi[:2] + 0.2 * (hi[:2] - lo[:2])), axis=1)
    keep &= inside[tri].any(1)
    img = np.ones((n, n, 3))
    depth = np.full((n, n), -np.inf)
    mb.rasterise(img, depth, p2, p[:, 2], tri[keep], rgb[keep])
    return img.reshape(PANEL, mb.SS, PANEL, mb.SS, 3).mean(axis=(1, 3))


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    case_dir, frame, out = sys.argv[1:4]
    methods = sys.argv[4:] or ["elastic", "corrective-smooth"]
    bind, faces = mb.read_obj(os.path.join(case_dir, "bind.obj"))
    ids = read_patch_ids(os.path.join(case_dir, "patch.txt"))
    fr, _ = mb.read_obj(os.path.join(case_dir, "frames", frame))
    views = [("frame", fr)] + [(m, mb.read_obj(os.path.join(case_dir, m, frame))[0])
                               for m in methods]
    pv = np.unique([v for i in ids for v in faces[i]])
    X = fr[pv] - fr[pv].mean(0)
    _, _, Vt = np.linalg.svd(X, full_matrices=False)
    look = Vt[1]
    up = Vt[0]
    side = np.cross(up, look)
    rots = [np.stack([side, up, look]), np.stack([-side, up, -look])]
    patch = [faces[i] for i in ids]
    in_patch = np.zeros(len(faces), bool)
    in_patch[ids] = True
    order = list(ids) + [i for i in range(len(faces)) if not in_patch[i]]
    ordered = [faces[i] for i in order]
    grey = np.array([0.72, 0.72, 0.72])
    nf = normals(fr, faces)
    cols = []
    labels = []
    for name, P in views:
        stretch, edge_logs = mb.face_stretch(P, bind, patch)
        rgb = mb.colour(stretch / mb.RANGE)
        flipped = np.einsum("ij,ij->i", normals(P, patch), nf[ids]) < 0
        rgb[flipped] = 0.0
        face_rgb = np.vstack([rgb, np.tile(grey, (len(faces) - len(ids), 1))])
        cols.append(face_rgb)
        labels.append((name, float(np.std(edge_logs)), int(flipped.sum())))
    gap, top, bottom = 12, 40, 40
    width = len(views) * (PANEL + gap) + gap
    img = np.ones((top + 2 * (PANEL + bottom), width, 3))
    for r, R in enumerate(rots):
        p = fr[pv] @ R.T
        lo, hi = p.min(0), p.max(0)
        pad = 0.06 * (hi - lo)
        box = (lo - pad, hi + pad)
        for k, ((name, P), face_rgb) in enumerate(zip(views, cols)):
            x = gap + k * (PANEL + gap)
            y = top + r * (PANEL + bottom)
            img[y:y + PANEL, x:x + PANEL] = render(P, ordered, face_rgb, R, box)
            if r == 0:
                mb.text(img, x + PANEL // 2, 12, name.upper(), centre=True)
            nm, spread, flips = labels[k]
            mb.text(img, x + PANEL // 2, y + PANEL + 8,
                    "SPREAD %.3f FLIPS %d" % (spread, flips), centre=True)
    mb.write_png(out, img)
    print("%s: %s" % (out, ", ".join("%s spread %.4f flips %d" % l for l in labels)))


if __name__ == "__main__":
    main()
