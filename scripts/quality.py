#!/usr/bin/python3
"""Helper of scripts/quality.sh: builds the benchmark's inputs and measures the slid frames.

Run with /usr/bin/python3 (standard library + numpy + scipy). The measures come from
/work/shared/reference/metrics.py (override with QUALITY_REFERENCE=DIR), imported as a module.

    quality.py gltf-bind FILE.glb OUT.obj
        The mesh as stored (POSITION of every TRIANGLES primitive of mesh 0), welded as
        skinslide welds it: vertices with exactly the same position are one, numbered by
        their first raw occurrence; faces = the triangles in primitive order. Written as
        an OBJ with `v` and `f` lines only.
    quality.py band BIND.obj LO HI AXIS OUT.txt [--rule centroid|all]
        Faces of BIND whose centroid (mean of the corners; --rule all: every corner) lies
        between LO and HI, fractions of the bind's extent along AXIS (x, y, z, or `longest` =
        the longest bounding-box axis).
    quality.py sphere BIND.obj FIRST LAST CX CY CZ R OUT.txt
        Faces FIRST..LAST whose centroid (mean of its corners) lies within distance R of
        (CX, CY, CZ), then only the edge-connected component holding the most faces.
    quality.py range FIRST LAST OUT.txt
        Faces FIRST..LAST.
        (All patch files are written as plain whitespace-separated face ids, the only syntax
        the reference's read_patch takes; skinslide reads it too.)
    quality.py patchinfo BIND.obj PATCH.txt
        One line: faces, vertices, edge-connected components, boundary loops, non-manifold
        (bow-tie) vertices.
    quality.py same DIR_A DIR_B
        Exit 1 unless every *.obj of DIR_A has the same vertex positions and faces as the
        file of the same name in DIR_B; prints the largest difference.
    quality.py measure --case C --method M --bind B --patch P --frames DIR --slid DIR
                       [--sequence] [--seconds S] [--json FILE]
        Prints one Markdown table row (columns: see HEADER below). Frames = DIR/*.obj in
        name order; each slid frame has the frame's file name in --slid. --sequence: the
        frames are consecutive times of an animation (popping figures); else those print "-".
        --seconds: wall clock of the command that made --slid (printed per frame).
        --period N: the motion's period in frames for the jerk index (default: the frame count).
    quality.py header
        Prints the table header.
"""
import argparse
import glob
import json
import math
import os
import struct
import sys

import numpy as np

REF = os.environ.get("QUALITY_REFERENCE", "/work/shared/reference")
sys.path.insert(0, REF)
from oracle import read_obj, read_patch  # noqa: E402
import metrics  # noqa: E402

HEADER = ("| case | method | frames | flips | spread mean | spread worst | improved | "
          "on-surface max | border max dev | outside max dev | pop mean | pop p99 | "
          "jitter mean | jitter p99 | jitter max | jerk | s/frame |")
RULE = "|" + "---|" * 17


# ---------------------------------------------------------------- glTF bind

def _load_gltf(path):
    data = open(path, "rb").read()
    if data[:4] == b"glTF":
        n = struct.unpack("<I", data[12:16])[0]
        doc = json.loads(data[20:20 + n])
        off = 20 + n
        chunk = b""
        if off < len(data):
            clen = struct.unpack("<I", data[off:off + 4])[0]
            chunk = data[off + 8:off + 8 + clen]
    else:
        doc, chunk = json.loads(data), b""
    bufs = []
    for b in doc.get("buffers", []):
        uri = b.get("uri")
        if uri is None:
            bufs.append(chunk)
        elif uri.startswith("data:"):
            import base64
            bufs.append(base64.b64decode(uri.split(",", 1)[1]))
        else:
            bufs.append(open(os.path.join(os.path.dirname(path), uri), "rb").read())
    return doc, bufs


def _accessor(doc, bufs, index):
    a = doc["accessors"][index]
    if "sparse" in a or a.get("normalized"):
        raise SystemExit("quality.py: sparse/normalized accessors are not handled here")
    v = doc["bufferViews"][a["bufferView"]]
    width = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}[a["type"]]
    dt = {5121: np.uint8, 5123: np.uint16, 5125: np.uint32, 5126: np.float32}[a["componentType"]]
    size = np.dtype(dt).itemsize * width
    stride = v.get("byteStride", size)
    base = v.get("byteOffset", 0) + a.get("byteOffset", 0)
    raw = bufs[v["buffer"]]
    out = np.empty((a["count"], width), dt)
    for i in range(a["count"]):
        out[i] = np.frombuffer(raw, dt, width, base + i * stride)
    return out


def cmd_gltf_bind(args):
    doc, bufs = _load_gltf(args.glb)
    mesh = doc["meshes"][0]
    index = {}
    verts = []
    tris = []
    for prim in mesh["primitives"]:
        if prim.get("mode", 4) != 4:
            continue
        P = _accessor(doc, bufs, prim["attributes"]["POSITION"])
        ids = np.empty(len(P), np.int64)
        for i, p in enumerate(P):
            key = tuple(float(c) for c in p)   # float32 -> exact double; 0.0 == -0.0
            w = index.get(key)
            if w is None:
                w = index[key] = len(verts)
                verts.append(key)
            ids[i] = w
        if "indices" in prim:
            I = _accessor(doc, bufs, prim["indices"]).reshape(-1).astype(np.int64)
        else:
            I = np.arange(len(P), dtype=np.int64)
        tris.extend(ids[I].reshape(-1, 3).tolist())
    with open(args.out, "w") as fh:
        fh.write("# welded bind of %s (quality.py gltf-bind)\n" % os.path.basename(args.glb))
        for p in verts:
            fh.write("v %r %r %r\n" % p)
        for t in tris:
            fh.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))
    print("%d welded vertices, %d triangles" % (len(verts), len(tris)))


# ---------------------------------------------------------------- patches

def write_patch(path, ids, comment):
    ids = sorted(int(i) for i in ids)
    if not ids:
        raise SystemExit("quality.py: empty patch for %s" % path)
    with open(path, "w") as fh:
        fh.write("# %s\n" % comment)
        for k in range(0, len(ids), 16):
            fh.write(" ".join(str(i) for i in ids[k:k + 16]) + "\n")


def patch_info(faces, ids):
    """faces (list of lists), ids: face ids -> dict of topology figures."""
    pf = [faces[i] for i in ids]
    # edge -> faces
    emap = {}
    for k, f in enumerate(pf):
        for j in range(len(f)):
            a, b = f[j], f[(j + 1) % len(f)]
            emap.setdefault((min(a, b), max(a, b)), []).append(k)
    # edge-connected components (union-find)
    parent = list(range(len(pf)))

    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x
    for fs in emap.values():
        for o in fs[1:]:
            ra, rb = find(fs[0]), find(o)
            if ra != rb:
                parent[ra] = rb
    comps = {}
    for k in range(len(pf)):
        comps.setdefault(find(k), []).append(k)
    bedges = [e for e, fs in emap.items() if len(fs) == 1]
    nonmanifold_edges = sum(1 for fs in emap.values() if len(fs) > 2)
    # boundary loops: components of the boundary-edge graph
    adj = {}
    for a, b in bedges:
        adj.setdefault(a, []).append(b)
        adj.setdefault(b, []).append(a)
    bowtie = sum(1 for v, n in adj.items() if len(n) != 2)
    seen = set()
    loops = 0
    for v in adj:
        if v in seen:
            continue
        loops += 1
        stack = [v]
        seen.add(v)
        while stack:
            x = stack.pop()
            for y in adj[x]:
                if y not in seen:
                    seen.add(y)
                    stack.append(y)
    # vertices where the faces around do not form one fan (bow-tie through a vertex)
    vf = {}
    for k, f in enumerate(pf):
        for v in f:
            vf.setdefault(v, []).append(k)
    fan_bad = 0
    for v, fs in vf.items():
        if len(fs) == 1:
            continue
        sub = {k: k for k in fs}

        def fnd(x):
            while sub[x] != x:
                x = sub[x]
            return x
        for k in fs:
            f = pf[k]
            j = f.index(v)
            for w in (f[j - 1], f[(j + 1) % len(f)]):
                for o in emap[(min(v, w), max(v, w))]:
                    if o in sub:
                        ra, rb = fnd(k), fnd(o)
                        if ra != rb:
                            sub[ra] = rb
        if len({fnd(k) for k in fs}) > 1:
            fan_bad += 1
    nverts = len(vf)
    sizes = sorted((len(c) for c in comps.values()), reverse=True)
    return {"faces": len(pf), "vertices": nverts, "components": len(comps),
            "component_faces": sizes, "loops": loops,
            "bowtie_vertices": max(bowtie, fan_bad), "nonmanifold_edges": nonmanifold_edges,
            "comp_lists": [[ids[k] for k in c] for c in comps.values()]}


def _fmt_info(info):
    return ("%d faces, %d vertices, %d component(s) %s, %d boundary loop(s), %d bow-tie vertices, "
            "%d non-manifold edges" % (info["faces"], info["vertices"], info["components"],
                                       info["component_faces"], info["loops"],
                                       info["bowtie_vertices"], info["nonmanifold_edges"]))


def cmd_band(args):
    V, faces, _ = read_obj(args.bind)
    lo_all, hi_all = V.min(0), V.max(0)
    ext = hi_all - lo_all
    axis = int(np.argmax(ext)) if args.axis == "longest" else "xyz".index(args.axis)
    lo = lo_all[axis] + args.lo * ext[axis]
    hi = lo_all[axis] + args.hi * ext[axis]
    if args.rule == "all":
        ids = [i for i, f in enumerate(faces) if all(lo <= V[v, axis] <= hi for v in f)]
    else:
        ids = [i for i, f in enumerate(faces) if lo <= V[f, axis].mean() <= hi]
    rule = ("faces with %s at %s in [%.6g, %.6g] (%.3g..%.3g of the bind's extent %.6g..%.6g)"
            % ("every corner" if args.rule == "all" else "centroid", "xyz"[axis], lo, hi,
               args.lo, args.hi, lo_all[axis], hi_all[axis]))
    write_patch(args.out, ids, rule)
    info = patch_info(faces, ids)
    print("%s; %s" % (rule, _fmt_info(info)))


def cmd_sphere(args):
    V, faces, _ = read_obj(args.bind)
    c = np.array([args.cx, args.cy, args.cz])
    ids = [i for i in range(args.first, args.last + 1)
           if np.linalg.norm(V[faces[i]].mean(0) - c) <= args.r]
    info = patch_info(faces, ids)
    if info["components"] > 1:
        ids = max(info["comp_lists"], key=len)
        info = patch_info(faces, ids)
    rule = ("faces %d-%d with centroid within %g of (%g, %g, %g), largest edge-connected component"
            % (args.first, args.last, args.r, args.cx, args.cy, args.cz))
    write_patch(args.out, ids, rule)
    print("%s; %s" % (rule, _fmt_info(info)))


def cmd_range(args):
    write_patch(args.out, range(args.first, args.last + 1), "faces %d-%d" % (args.first, args.last))


def cmd_patchinfo(args):
    V, faces, _ = read_obj(args.bind)
    ids = [int(i) for i in read_patch(args.patch, len(faces))]
    print(_fmt_info(patch_info(faces, ids)))


def cmd_same(args):
    worst = 0.0
    names = sorted(os.path.basename(p) for p in glob.glob(os.path.join(args.a, "*.obj")))
    if not names:
        raise SystemExit("quality.py same: no OBJ in %s" % args.a)
    for n in names:
        Va, Fa, _ = read_obj(os.path.join(args.a, n))
        Vb, Fb, _ = read_obj(os.path.join(args.b, n))
        if Fa != Fb or Va.shape != Vb.shape:
            print("%s: topology differs" % n)
            return 1
        worst = max(worst, float(np.abs(Va - Vb).max()))
    print("%d frames, largest coordinate difference %g" % (len(names), worst))
    return 0 if worst == 0.0 else 1


# ---------------------------------------------------------------- measure

def _g(x, digits=3):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "nan"
    if x == 0:
        return "0"
    return "%.*g" % (digits, x)


def _second_diff_norms(X):
    """X: (T, n, 3) -> (T-2, n) Euclidean norms of X[t+1] - 2 X[t] + X[t-1]."""
    return np.linalg.norm(X[2:] - 2.0 * X[1:-1] + X[:-2], axis=2)


def free_vertices(faces, ids):
    """Patch vertices on no patch boundary edge (an edge used by one patch face): the ones a
    slide may move."""
    cnt = {}
    for i in ids:
        f = faces[i]
        for k in range(len(f)):
            e = (min(f[k], f[(k + 1) % len(f)]), max(f[k], f[(k + 1) % len(f)]))
            cnt[e] = cnt.get(e, 0) + 1
    border = {v for e, c in cnt.items() if c == 1 for v in e}
    return np.array(sorted({v for i in ids for v in faces[i]} - border), np.int64)


def mean_edge_length(V, faces, ids):
    """Mean length of the patch's distinct edges in V."""
    e = set()
    for i in ids:
        f = faces[i]
        for k in range(len(f)):
            a, b = f[k], f[(k + 1) % len(f)]
            e.add((min(a, b), max(a, b)))
    e = np.array(sorted(e))
    return float(np.linalg.norm(V[e[:, 0]] - V[e[:, 1]], axis=1).mean())


def jitter(S, edge, period):
    """S: (T, n, 3) slide (slid - frame) of the free vertices over consecutive frames.
    -> dict: second difference |S[t+1] - 2 S[t] + S[t-1]| in units of `edge` (mean, p99, max
    over vertices and interior times) and the jerk index mean |d2 S| / mean |d S| / (2 pi /
    period) (None when the slide never moves)."""
    d2 = _second_diff_norms(S) / edge
    d1 = np.linalg.norm(S[1:] - S[:-1], axis=2) / edge
    out = {"jitter_mean": float(d2.mean()), "jitter_p99": float(np.percentile(d2, 99)),
           "jitter_max": float(d2.max()), "period": period, "edge": edge}
    m1 = float(d1.mean())
    out["jerk"] = float(d2.mean()) / m1 / (2 * math.pi / period) if m1 > 0 else None
    return out


def cmd_measure(args):
    names = sorted(os.path.basename(p) for p in glob.glob(os.path.join(args.frames, "*.obj")))
    if not names:
        raise SystemExit("quality.py measure: no frames in %s" % args.frames)
    Vb, bfaces, _ = read_obj(args.bind)
    patch = read_patch(args.patch, len(bfaces))
    pverts = np.unique([v for i in patch for v in bfaces[i]])
    fverts = free_vertices(bfaces, patch)
    flips = 0
    ratios = []
    at_bind = 0
    on_surf = 0.0
    border = 0.0
    outside = 0.0
    nan = 0
    F_seq, S_seq = [], []
    per_frame = []
    for n in names:
        fp = os.path.join(args.frames, n)
        sp = os.path.join(args.slid, n)
        if not os.path.exists(sp):
            raise SystemExit("quality.py measure: %s has no slid frame %s" % (fp, sp))
        m = metrics.compute(args.bind, args.patch, fp, sp)
        if "error" in m:
            raise SystemExit("quality.py measure: %s: %s" % (sp, m["error"]))
        if args.check_topology:
            _, ff, _ = read_obj(fp)
            if ff != bfaces:
                raise SystemExit("quality.py measure: %s: faces differ from the bind's" % fp)
        per_frame.append(dict(m, frame=n))
        nan += m["nan_count"]
        flips += m["flips"]
        on_surf = max(on_surf, m["on_surface_max_rel"])
        border = max(border, m["boundary_max_dev"])
        outside = max(outside, m["outside_max_dev"])
        lf = m["edge_logstd_frame"]
        if lf is None or lf < 1e-9:
            at_bind += 1
        else:
            ratios.append(m["edge_logstd_slid"] / lf)
        if args.sequence:
            F_seq.append(read_obj(fp)[0][pverts])
            S_seq.append(read_obj(sp)[0][pverts])
    T = len(names)
    row = [args.case, args.method, str(T) if not at_bind else "%d (%d at bind)" % (T, at_bind),
           str(flips) + (" (%d NaN)" % nan if nan else "")]
    if ratios:
        r = np.array(ratios)
        row += [_g(float(r.mean())), _g(float(r.max())), "%d of %d" % (int((r < 1).sum()), len(r))]
    else:
        row += ["-", "-", "0 of 0"]
    row += [_g(on_surf, 2), _g(border, 2), _g(outside, 2)]
    pop = {}
    if args.sequence and T >= 3:
        F = np.stack(F_seq)
        S = np.stack(S_seq)
        aF = _second_diff_norms(F)
        aS = _second_diff_norms(S)
        aD = _second_diff_norms(S - F)
        base = float(aF.mean())
        pop = {"pop_mean": float(aS.mean()) / base, "pop_p99": float(np.percentile(aD, 99)) / base}
        row += [_g(pop["pop_mean"], 4), _g(pop["pop_p99"])]
        # the jitter figures: the free vertices' slide in units of the mean bind edge
        free_in = np.searchsorted(pverts, fverts)
        jit = jitter((S - F)[:, free_in], mean_edge_length(Vb, bfaces, patch),
                     args.period or T)
        pop.update(jit)
        row += [_g(jit["jitter_mean"]), _g(jit["jitter_p99"]), _g(jit["jitter_max"]),
                "-" if jit["jerk"] is None else _g(jit["jerk"])]
    else:
        row += ["-"] * 6
    row.append("-" if args.seconds is None else "%.3g" % (args.seconds / T))
    print("| " + " | ".join(row) + " |")
    if args.json:
        with open(args.json, "a") as fh:
            fh.write(json.dumps({"case": args.case, "method": args.method, "frames": per_frame,
                                 "ratios": ratios, "pop": pop, "seconds": args.seconds}) + "\n")
    return 0


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("gltf-bind"); p.add_argument("glb"); p.add_argument("out")
    p.set_defaults(fn=cmd_gltf_bind)
    p = sub.add_parser("band"); p.add_argument("bind"); p.add_argument("lo", type=float)
    p.add_argument("hi", type=float); p.add_argument("axis", choices=["x", "y", "z", "longest"])
    p.add_argument("out"); p.add_argument("--rule", choices=["centroid", "all"], default="centroid")
    p.set_defaults(fn=cmd_band)
    p = sub.add_parser("sphere"); p.add_argument("bind")
    for k in ("first", "last"):
        p.add_argument(k, type=int)
    for k in ("cx", "cy", "cz", "r"):
        p.add_argument(k, type=float)
    p.add_argument("out"); p.set_defaults(fn=cmd_sphere)
    p = sub.add_parser("range"); p.add_argument("first", type=int); p.add_argument("last", type=int)
    p.add_argument("out"); p.set_defaults(fn=cmd_range)
    p = sub.add_parser("patchinfo"); p.add_argument("bind"); p.add_argument("patch")
    p.set_defaults(fn=cmd_patchinfo)
    p = sub.add_parser("same"); p.add_argument("a"); p.add_argument("b"); p.set_defaults(fn=cmd_same)
    p = sub.add_parser("measure")
    for k in ("--case", "--method", "--bind", "--patch", "--frames", "--slid"):
        p.add_argument(k, required=True)
    p.add_argument("--sequence", action="store_true")
    p.add_argument("--period", type=float,
                   help="N of the jerk index (frames of the motion's period; default: the frames)")
    p.add_argument("--check-topology", action="store_true",
                   help="also check that every frame has the bind's faces")
    p.add_argument("--seconds", type=float)
    p.add_argument("--json")
    p.set_defaults(fn=cmd_measure)
    p = sub.add_parser("header")
    p.set_defaults(fn=lambda a: print(HEADER + "\n" + RULE))
    args = ap.parse_args(argv)
    return args.fn(args) or 0


if __name__ == "__main__":
    sys.exit(main())
