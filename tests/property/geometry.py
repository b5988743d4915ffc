"""Geometry for the invariants: fan triangles, point-to-triangle distances (a uniform grid so a
whole patch of a large mesh is measured in well under a second), bounding-box diagonals."""
from fractions import Fraction

import numpy as np


def fan_triangles(faces):
    """Polygons as skinslide triangulates them for location: (v0, vk+1, vk+2)."""
    out = []
    for f in faces:
        for k in range(len(f) - 2):
            out.append((f[0], f[k + 1], f[k + 2]))
    return np.array(out, dtype=np.int64).reshape(-1, 3)


def diagonal(points):
    points = np.asarray(points)
    if len(points) == 0:
        return 0.0
    return float(np.linalg.norm(points.max(axis=0) - points.min(axis=0)))


def _segment_distance(p, a, b):
    ab = b - a
    den = np.einsum("ij,ij->i", ab, ab)
    t = np.einsum("ij,ij->i", p - a, ab)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(den > 0, t / np.where(den > 0, den, 1), 0.0)
    t = np.clip(t, 0.0, 1.0)
    return np.linalg.norm(p - (a + t[:, None] * ab), axis=1)


def pair_distances(p, a, b, c):
    """Distance from each point p[i] to triangle (a[i], b[i], c[i]); degenerate triangles are
    measured by their edges."""
    e0, e1 = b - a, c - a
    v2 = p - a
    d00 = np.einsum("ij,ij->i", e0, e0)
    d01 = np.einsum("ij,ij->i", e0, e1)
    d11 = np.einsum("ij,ij->i", e1, e1)
    d20 = np.einsum("ij,ij->i", v2, e0)
    d21 = np.einsum("ij,ij->i", v2, e1)
    den = d00 * d11 - d01 * d01
    ok = den > 1e-28 * np.maximum(d00 * d11, 1e-300)
    safe = np.where(ok, den, 1.0)
    v = (d11 * d20 - d01 * d21) / safe
    w = (d00 * d21 - d01 * d20) / safe
    inside = ok & (v >= 0) & (w >= 0) & (v + w <= 1)
    n = np.cross(e0, e1)
    nn = np.linalg.norm(n, axis=1)
    plane = np.abs(np.einsum("ij,ij->i", v2, n)) / np.where(nn > 0, nn, 1.0)
    d = np.minimum(_segment_distance(p, a, b), _segment_distance(p, b, c))
    d = np.minimum(d, _segment_distance(p, c, a))
    return np.where(inside, np.minimum(plane, d), d)


def distances_to_triangles(points, corners, reach):
    """For each point, its distance to the nearest triangle (corners: (T, 3, 3)), exact for
    distances up to `reach` (farther ones are reported as at least reach, possibly inf)."""
    points = np.asarray(points, dtype=np.float64)
    m, t = len(points), len(corners)
    best = np.full(m, np.inf)
    if m == 0 or t == 0:
        return best
    if m * t <= 2_000_000:
        for s in range(0, m, max(1, 2_000_000 // t)):
            q = points[s:s + max(1, 2_000_000 // t)]
            pi = np.repeat(np.arange(len(q)), t)
            ti = np.tile(np.arange(t), len(q))
            d = pair_distances(q[pi], corners[ti, 0], corners[ti, 1], corners[ti, 2])
            best[s:s + len(q)] = d.reshape(len(q), t).min(axis=1)
        return best
    lo_t = corners.min(axis=1) - reach
    hi_t = corners.max(axis=1) + reach
    ext = hi_t - lo_t
    h = max(float(np.median(ext.max(axis=1))), 1e-300)
    origin = lo_t.min(axis=0)
    span = (hi_t.max(axis=0) - origin)
    h = max(h, float(span.max()) / 2**19)
    dims = np.floor(span / h).astype(np.int64) + 1
    i0 = np.floor((lo_t - origin) / h).astype(np.int64)
    i1 = np.floor((hi_t - origin) / h).astype(np.int64)
    fits = np.all(i1 - i0 < 3, axis=1)  # at most 3 cells along each axis
    big = np.flatnonzero(~fits)
    small = np.flatnonzero(fits)
    keys, tris = [], []
    for dx in range(3):
        for dy in range(3):
            for dz in range(3):
                c = i0[small] + np.array([dx, dy, dz])
                ok = np.all(c <= i1[small], axis=1)
                c = c[ok]
                keys.append(c[:, 0] + dims[0] * (c[:, 1] + dims[1] * c[:, 2]))
                tris.append(small[ok])
    keys = np.concatenate(keys)
    tris = np.concatenate(tris)
    order = np.argsort(keys, kind="stable")
    keys, tris = keys[order], tris[order]
    pc = np.floor((points - origin) / h).astype(np.int64)
    inside = np.all((pc >= 0) & (pc < dims), axis=1)
    pk = pc[:, 0] + dims[0] * (pc[:, 1] + dims[1] * pc[:, 2])
    start = np.searchsorted(keys, pk, "left")
    stop = np.searchsorted(keys, pk, "right")
    count = np.where(inside, stop - start, 0)
    pi = np.repeat(np.arange(m), count)
    offs = np.arange(len(pi)) - np.repeat(np.cumsum(count) - count, count)
    ti = tris[np.repeat(start, count) + offs]
    if len(pi):
        d = pair_distances(points[pi], corners[ti, 0], corners[ti, 1], corners[ti, 2])
        np.minimum.at(best, pi, d)
    for b in big:
        d = pair_distances(points, np.broadcast_to(corners[b, 0], points.shape),
                           np.broadcast_to(corners[b, 1], points.shape),
                           np.broadcast_to(corners[b, 2], points.shape))
        best = np.minimum(best, d)
    return best


def _exact_distance2(p, a, b, c):
    """Squared distance from p to triangle abc in exact rational arithmetic (from the doubles'
    exact values): the arbiter where the double formulas cancel (slivers)."""
    p, a, b, c = ([Fraction(float(x)) for x in v] for v in (p, a, b, c))

    def sub(u, v):
        return [u[0] - v[0], u[1] - v[1], u[2] - v[2]]

    def dot(u, v):
        return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]

    def seg2(q, u, v):
        d = sub(v, u)
        dd = dot(d, d)
        t = Fraction(0) if dd == 0 else min(max(dot(sub(q, u), d) / dd, Fraction(0)), Fraction(1))
        x = [u[k] + t * d[k] - q[k] for k in range(3)]
        return dot(x, x)

    e0, e1, v2 = sub(b, a), sub(c, a), sub(p, a)
    d00, d01, d11 = dot(e0, e0), dot(e0, e1), dot(e1, e1)
    d20, d21 = dot(v2, e0), dot(v2, e1)
    den = d00 * d11 - d01 * d01
    best = min(seg2(p, a, b), seg2(p, b, c), seg2(p, c, a))
    if den > 0:
        v = (d11 * d20 - d01 * d21) / den
        w = (d00 * d21 - d01 * d20) / den
        if v >= 0 and w >= 0 and v + w <= 1:
            q = [a[k] + v * e0[k] + w * e1[k] - p[k] for k in range(3)]
            best = min(best, dot(q, q))
    return best


def exact_within(point, corners, limit):
    """Whether `point` lies within `limit` of one of the triangles (T, 3, 3), decided exactly;
    the triangles whose boxes are farther are not measured."""
    lo = corners.min(axis=1) - limit
    hi = corners.max(axis=1) + limit
    near = np.flatnonzero(np.all((point >= lo) & (point <= hi), axis=1))
    lim2 = Fraction(float(limit)) ** 2
    return any(_exact_distance2(point, *corners[t]) <= lim2 for t in near)
