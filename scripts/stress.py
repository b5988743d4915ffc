#!/usr/bin/python3
"""Helper of scripts/stress.sh: the elastic energy measured from outside, converged references
(cached on disk), and one table row per case and method.

Run with /usr/bin/python3 (numpy, scipy). Flips, on-surface, border, outside and spread come from
/work/shared/reference/metrics.py (QUALITY_REFERENCE=DIR overrides), as in scripts/quality.py.

    stress.py energy BIND PATCH FRAME SLID
        One JSON object: the ARAP energy of FRAME and of SLID, computed here from positions alone
        by rules 3-4 of lib/elastic/README.md: the patch split into edge-connected components;
        polygons fanned (v0, vi, vi+1); per component and triangle the deformation gradient
        J = [x_b - x_a, x_c - x_a] D, D the inverse of the bind edge matrix in the triangle's own
        plane; triangles with 2 |area| <= 1e-12 (|e1|^2 + |e2|^2 + |e2 - e1|^2) have no rest
        shape and no energy; E = w sum (s1 - s)^2 + (s2 - s)^2 over the others (s1, s2 the
        singular values of J), w = the component's bind area / its triangle count (every
        triangle), s = sqrt(frame area / bind area) of the component. Energies add over
        components.
    stress.py reference --case C --bind B --patch P --frames DIR --work DIR --cache DIR
                        --skinslide BIN --skinslide-args ARGS [--skinslide-rounds-args ARGS]
                        --prototype PY --prototype-args ARGS
                        [--prototype-max-free N] [--prototype-timeout S] [--kinds K,K] --out JSON
        The converged reference of every frame: the lowest energy of (a) BIN with ARGS (its most
        thorough steps; the frames not cached, in one command), (a') BIN with the rounds' ARGS
        (many rotation fits of a few steps each: ARAP's local/global alternation gains slowly on
        patches that bend freely, and ten fits stopped a whole head 25-30% above what three
        hundred reach) and (b) the Python prototype PY with ARGS (exact sparse LU Newton; one
        process a frame), (b) only when the patch has at most N free vertices and only for
        frames it finishes within S seconds (a frame over it has no prototype figure). Each frame's energy from each is cached in --cache
        under a key of the inputs' bytes, the program's bytes and the arguments, so a rerun
        reads it instead of solving again (and a run cut short keeps what it finished).
        --kinds skinslide, skinslide-rounds or prototype alone fills one cache (the prototype's needs no
        binary). Writes JSON: per frame the reference energy, which run gave it, each run's.
    stress.py measure --case C --method M --bind B --patch P --frames DIR --slid DIR
                      [--report JSON] [--reference JSON] [--seconds S] [--json FILE]
        Prints one Markdown row (columns: HEADER). --report: skinslide's --report file for
        the stops and the step solves' iterations; --reference: the file `reference` wrote.
    stress.py header
"""
import argparse
import glob
import hashlib
import json
import math
import os
import subprocess
import sys
import time

import numpy as np
import scipy.sparse as sp
import scipy.sparse.csgraph as csg

REF = os.environ.get("QUALITY_REFERENCE", "/work/shared/reference")
sys.path.insert(0, REF)
from oracle import read_obj, read_patch  # noqa: E402
import metrics  # noqa: E402
from quality import free_vertices  # noqa: E402  (scripts/, the script's own folder)

GAP_TARGET = 0.05   # issue 28: every frame within 5% of its converged reference

HEADER = ("| case | method | frames | flips | on-surface max | border / outside max dev | "
          "spread mean | energy left mean / max | gap to reference max | within 5% | "
          "stops (frame x patch) | solve it./solve mean / max | converged above 5% | s/frame |")
RULE = "|" + "---|" * 14


# ---------------------------------------------------------------- energy

def fan(faces, ids):
    T = []
    for i in ids:
        f = faces[i]
        for k in range(1, len(f) - 1):
            T.append((f[0], f[k], f[k + 1]))
    return np.array(T, np.int64).reshape(-1, 3)


def components(faces, ids):
    """Edge-connected components of the patch faces -> list of face-id lists."""
    ids = list(ids)
    edges = {}
    for k, i in enumerate(ids):
        f = faces[i]
        for j in range(len(f)):
            a, b = f[j], f[(j + 1) % len(f)]
            edges.setdefault((min(a, b), max(a, b)), []).append(k)
    r, c = [], []
    for fs in edges.values():
        for o in fs[1:]:
            r.append(fs[0])
            c.append(o)
    n = len(ids)
    A = sp.coo_matrix((np.ones(len(r)), (r, c)), shape=(n, n))
    nc, lab = csg.connected_components(A, directed=False)
    return [[ids[k] for k in np.nonzero(lab == q)[0]] for q in range(nc)]


class Energy:
    """Precomputed per bind and patch; __call__(X, Xf) -> energy of X against frame Xf."""

    def __init__(self, Vb, faces, ids):
        self.parts = []
        for comp in components(faces, ids):
            T = fan(faces, comp)
            f1 = Vb[T[:, 1]] - Vb[T[:, 0]]
            f2 = Vb[T[:, 2]] - Vb[T[:, 0]]
            l1 = np.linalg.norm(f1, axis=1)
            twice = np.linalg.norm(np.cross(f1, f2), axis=1)
            scale = (f1 ** 2).sum(1) + (f2 ** 2).sum(1) + ((f2 - f1) ** 2).sum(1)
            ok = (l1 > 0) & (twice > 1e-12 * scale)
            ex = f1[ok] / l1[ok, None]
            B = np.zeros((int(ok.sum()), 2, 2))
            B[:, 0, 0] = l1[ok]
            B[:, 0, 1] = np.einsum("ij,ij->i", f2[ok], ex)
            B[:, 1, 1] = twice[ok] / l1[ok]
            area = 0.5 * float(twice.sum())
            self.parts.append({"T": T, "ok": ok, "D": np.linalg.inv(B), "area": area,
                               "w": area / len(T), "excluded": int((~ok).sum())})

    def __call__(self, X, Xf):
        total = 0.0
        for p in self.parts:
            T = p["T"]
            af = 0.5 * np.linalg.norm(np.cross(Xf[T[:, 1]] - Xf[T[:, 0]],
                                               Xf[T[:, 2]] - Xf[T[:, 0]]), axis=1).sum()
            s = math.sqrt(af / p["area"]) if p["area"] > 0 else 1.0
            To = T[p["ok"]]
            E = np.stack([X[To[:, 1]] - X[To[:, 0]], X[To[:, 2]] - X[To[:, 0]]], 2)  # (n,3,2)
            J = E @ p["D"]
            sv = np.linalg.svd(J, compute_uv=False)
            total += p["w"] * float(((sv - s) ** 2).sum())
        return total

    @property
    def excluded(self):
        return sum(p["excluded"] for p in self.parts)


def cmd_energy(a):
    Vb, faces, _ = read_obj(a.bind)
    ids = read_patch(a.patch, len(faces))
    en = Energy(Vb, faces, ids)
    Xf = read_obj(a.frame)[0]
    Xs = read_obj(a.slid)[0]
    ef, es = en(Xf, Xf), en(Xs, Xf)
    print(json.dumps({"energy_frame": ef, "energy_slid": es,
                      "left": es / ef if ef > 0 else None, "excluded_triangles": en.excluded}))


# ---------------------------------------------------------------- references

def sha(*parts):
    h = hashlib.sha256()
    for p in parts:
        h.update(p if isinstance(p, bytes) else str(p).encode())
        h.update(b"\0")
    return h.hexdigest()


def file_bytes(path):
    with open(path, "rb") as fh:
        return fh.read()


def cmd_reference(a):
    Vb, faces, _ = read_obj(a.bind)
    ids = read_patch(a.patch, len(faces))
    en = Energy(Vb, faces, ids)
    names = sorted(os.path.basename(p) for p in glob.glob(os.path.join(a.frames, "*.obj")))
    base = sha(file_bytes(a.bind), file_bytes(a.patch))
    fkeys = {n: sha(base, file_bytes(os.path.join(a.frames, n))) for n in names}
    os.makedirs(a.cache, exist_ok=True)
    nfree = len(free_vertices(faces, ids))
    frame_E = {n: en(*(2 * [read_obj(os.path.join(a.frames, n))[0]])) for n in names}

    def energy_of(out_dir, n):
        Xf = read_obj(os.path.join(a.frames, n))[0]
        Xs = read_obj(os.path.join(out_dir, n))[0]
        return en(Xs, Xf)

    def cache_path(kind, program_key, n):
        return os.path.join(a.cache, "%s-%s-%s-%s.json" % (
            a.case, os.path.splitext(n)[0], kind, sha(kind, program_key, fkeys[n])[:24]))

    def store(path, rec):
        with open(path + ".tmp", "w") as fh:
            json.dump(rec, fh)
        os.replace(path + ".tmp", path)

    runs = {}
    kinds = set(a.kinds.split(","))

    # (a) skinslide at each of its most thorough settings: the frames not cached yet, in one
    # command a setting
    def skinslide_run(kind, args):
        key = sha(file_bytes(a.skinslide), args)
        todo = [n for n in names if not os.path.exists(cache_path(kind, key, n))]
        note = "cached"
        if todo:
            out = os.path.join(a.work, "ref-" + kind)
            rep = os.path.join(a.work, "ref-%s.json" % kind)
            cmd = [a.skinslide, "-q", "--method", "elastic"] + args.split() + [
                "--report", rep, "--patch", a.patch, "-o", out, a.bind] + \
                [os.path.join(a.frames, n) for n in todo]
            t0 = time.time()
            r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            dt = time.time() - t0
            if r.returncode != 0:
                sys.stderr.write(r.stderr[-2000:])
                raise SystemExit("stress.py reference: %s: skinslide exited %d: %s"
                                 % (a.case, r.returncode, " ".join(cmd)))
            stops = report_stops(rep)
            for n in todo:
                store(cache_path(kind, key, n),
                      {"energy": energy_of(out, n), "seconds": dt / len(todo),
                       "command": " ".join(cmd), "stops": stops.get(n)})
            note = "%.0f s for %d frame(s)" % (dt, len(todo))
        return ({n: json.load(open(cache_path(kind, key, n))) for n in names}, note)

    if "skinslide" in kinds:
        runs["skinslide"] = skinslide_run("skinslide", a.skinslide_args)
    if "skinslide-rounds" in kinds and a.skinslide_rounds_args:
        runs["skinslide-rounds"] = skinslide_run("skinslide-rounds", a.skinslide_rounds_args)
    # (b) the prototype, frame by frame, where it finishes in reasonable time
    if "prototype" in kinds:
        key = sha(file_bytes(a.prototype), a.prototype_args, a.prototype_timeout)
        if nfree > a.prototype_max_free:
            runs["prototype"] = ({}, "not run: %d free vertices > %d"
                                 % (nfree, a.prototype_max_free))
        else:
            spent, done = 0.0, 0
            for n in names:
                path = cache_path("prototype", key, n)
                if os.path.exists(path):
                    continue
                out = os.path.join(a.work, "ref-prototype")
                cmd = [sys.executable, a.prototype, a.bind, a.patch,
                       os.path.join(a.frames, n), "-o", out] + a.prototype_args.split()
                t0 = time.time()
                try:
                    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                       text=True, timeout=a.prototype_timeout)
                    rec = {"seconds": time.time() - t0, "command": " ".join(cmd)}
                    if r.returncode == 0:
                        rec["energy"] = energy_of(out, n)
                    else:
                        rec["energy"] = None
                        rec["note"] = "exit %d: %s" % (r.returncode, (r.stderr.strip().splitlines()
                                                                      or [""])[-1])
                except subprocess.TimeoutExpired:
                    rec = {"energy": None, "seconds": time.time() - t0, "command": " ".join(cmd),
                           "note": "timed out after %g s" % a.prototype_timeout}
                store(path, rec)
                spent += rec["seconds"]
                done += 1
            recs = {n: json.load(open(cache_path("prototype", key, n))) for n in names}
            bad = [r.get("note") for r in recs.values() if r.get("energy") is None]
            runs["prototype"] = (recs, ("%.0f s for %d frame(s)" % (spent, done) if done
                                        else "cached") + ("; %d frame(s) without: %s"
                                                          % (len(bad), bad[0]) if bad else ""))
    frames = {}
    for n in names:
        best, by = None, None
        each = {}
        for k, (recs, _) in runs.items():
            e = recs.get(n, {}).get("energy")
            each[k] = e
            if e is not None and (best is None or e < best):
                best, by = e, k
        frames[n] = {"energy_frame": frame_E[n], "reference": best, "by": by, "runs": each,
                     "reference_stops": (runs.get("skinslide", ({}, ""))[0].get(n) or {}).get(
                         "stops")}
    with open(a.out, "w") as fh:
        json.dump({"case": a.case, "free_vertices": nfree, "frames": frames,
                   "notes": {k: v[1] for k, v in runs.items()}}, fh, indent=1)
    for k, (_, note) in runs.items():
        print("%s: reference by %s: %s" % (a.case, k, note))


# ---------------------------------------------------------------- report

def report_stops(path):
    """skinslide --report JSON -> per frame file name, a list of per-patch dicts."""
    with open(path) as fh:
        rep = json.load(fh)
    out = {}
    for fr in rep.get("frames", []):
        name = os.path.basename(str(fr.get("output") or fr.get("input") or fr.get("frame", "")))
        pats = []
        for p in fr.get("patches", []):
            m = p.get("elastic") or p.get("method") or p
            pats.append({k: m.get(k) for k in ("stop", "iterations", "solves",
                                               "solve_iterations", "energy_before",
                                               "energy_after", "held", "flips")})
        out[name] = pats
    return out


# ---------------------------------------------------------------- measure

def _g(x, digits=3):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "nan"
    if x == 0:
        return "0"
    return "%.*g" % (digits, x)


def cmd_measure(a):
    names = sorted(os.path.basename(p) for p in glob.glob(os.path.join(a.frames, "*.obj")))
    Vb, faces, _ = read_obj(a.bind)
    ids = read_patch(a.patch, len(faces))
    en = Energy(Vb, faces, ids)
    ref = None
    if a.reference:
        with open(a.reference) as fh:
            ref = json.load(fh)
    stops = report_stops(a.report) if a.report else None
    flips = 0
    on_surf = border = outside = 0.0
    spreads, left, gaps, per = [], [], [], []
    stop_count = {}
    it_per_solve = []
    liars = 0
    for n in names:
        fp, spth = os.path.join(a.frames, n), os.path.join(a.slid, n)
        m = metrics.compute(a.bind, a.patch, fp, spth)
        if "error" in m:
            raise SystemExit("stress.py measure: %s: %s" % (spth, m["error"]))
        flips += m["flips"] + m["nan_count"]
        on_surf = max(on_surf, m["on_surface_max_rel"] or 0.0)
        border = max(border, m["boundary_max_dev"] or 0.0)
        outside = max(outside, m["outside_max_dev"] or 0.0)
        lf = m["edge_logstd_frame"]
        if lf and lf > 1e-9:
            spreads.append(m["edge_logstd_slid"] / lf)
        Xf = read_obj(fp)[0]
        Xs = read_obj(spth)[0]
        ef, es = en(Xf, Xf), en(Xs, Xf)
        rec = {"frame": n, "energy_frame": ef, "energy_slid": es,
               "left": es / ef if ef > 0 else None}
        if rec["left"] is not None:
            left.append(rec["left"])
        gap = None
        if ref and ref["frames"].get(n, {}).get("reference") is not None:
            er = ref["frames"][n]["reference"]
            gap = es / er - 1 if er > 0 else (0.0 if es <= 0 else math.inf)
            gaps.append(gap)
            rec["reference"] = er
            rec["gap"] = gap
        if stops is not None:
            pats = stops.get(n, [])
            rec["patches"] = pats
            for p in pats:
                s = p.get("stop") or "?"
                stop_count[s] = stop_count.get(s, 0) + 1
                if p.get("solves"):
                    it_per_solve.append(p["solve_iterations"] / p["solves"])
                if s == "converged" and gap is not None and gap > GAP_TARGET:
                    liars += 1
        per.append(rec)
    T = len(names)
    row = [a.case, a.method, str(T), str(flips), _g(on_surf, 2),
           "%s / %s" % (_g(border, 2), _g(outside, 2)),
           _g(float(np.mean(spreads))) if spreads else "-",
           "%s / %s" % (_g(float(np.mean(left))), _g(float(np.max(left)))) if left else "-"]
    if gaps:
        row += [("%+.3g" % max(gaps)) if math.isfinite(max(gaps)) else "inf",
                "%d of %d" % (sum(g <= GAP_TARGET for g in gaps), len(gaps))]
    else:
        row += ["-", "-"]
    if stops is not None:
        row.append(", ".join("%s %d" % (k, v) for k, v in sorted(stop_count.items())) or "-")
        row.append("%s / %s" % (_g(float(np.mean(it_per_solve))), _g(float(np.max(it_per_solve))))
                   if it_per_solve else "-")
        row.append(str(liars) if gaps else "-")
    else:
        row += ["-", "-", "-"]
    row.append("-" if a.seconds is None else "%.3g" % (a.seconds / T))
    print("| " + " | ".join(row) + " |")
    if a.json:
        with open(a.json, "a") as fh:
            fh.write(json.dumps({"case": a.case, "method": a.method, "frames": per,
                                 "seconds": a.seconds}) + "\n")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("energy")
    for k in ("bind", "patch", "frame", "slid"):
        p.add_argument(k)
    p.set_defaults(fn=cmd_energy)
    p = sub.add_parser("reference")
    for k in ("--case", "--bind", "--patch", "--frames", "--work", "--cache", "--out"):
        p.add_argument(k, required=True)
    for k in ("--skinslide", "--skinslide-args", "--skinslide-rounds-args", "--prototype",
              "--prototype-args"):
        p.add_argument(k, default="")
    p.add_argument("--prototype-max-free", type=int, default=4000)
    p.add_argument("--prototype-timeout", type=float, default=900,
                   help="seconds a frame (a frame over it has no prototype reference)")
    p.add_argument("--kinds", default="skinslide,skinslide-rounds,prototype")
    p.set_defaults(fn=cmd_reference)
    p = sub.add_parser("measure")
    for k in ("--case", "--method", "--bind", "--patch", "--frames", "--slid"):
        p.add_argument(k, required=True)
    p.add_argument("--report")
    p.add_argument("--reference")
    p.add_argument("--seconds", type=float)
    p.add_argument("--json")
    p.set_defaults(fn=cmd_measure)
    p = sub.add_parser("header")
    p.set_defaults(fn=lambda a: print(HEADER + "\n" + RULE))
    a = ap.parse_args(argv)
    return a.fn(a) or 0


if __name__ == "__main__":
    sys.exit(main())
