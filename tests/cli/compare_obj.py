#!/usr/bin/python3
"""Compare two OBJ files the way skinslide's golden tests do.

    compare_obj.py EXPECTED ACTUAL [--tol REL]

Every line that is not a `v` line must be byte-identical; `v` lines must have the same tokens
apart from x y z, which must agree within REL times the bounding-box diagonal of EXPECTED
(default 1e-9: golden files are compared to round-off, not bit for bit, so that a compiler or
libm change does not fail the suite while any real change of the method does).
Exit 0 when they match, 1 with a message naming the first difference otherwise.
"""
import math
import sys


def main(argv):
    tol = 1e-9
    args = list(argv)
    if "--tol" in args:
        i = args.index("--tol")
        tol = float(args[i + 1])
        del args[i:i + 2]
    exp_path, act_path = args
    exp = open(exp_path, "rb").read().split(b"\n")
    act = open(act_path, "rb").read().split(b"\n")
    if len(exp) != len(act):
        print("%s: %d lines, expected %d" % (act_path, len(act), len(exp)))
        return 1
    pts = [list(map(float, l.split()[1:4])) for l in exp if l.startswith(b"v ")]
    lo = [min(p[k] for p in pts) for k in range(3)]
    hi = [max(p[k] for p in pts) for k in range(3)]
    diag = math.sqrt(sum((hi[k] - lo[k]) ** 2 for k in range(3)))
    worst = 0.0
    for n, (a, b) in enumerate(zip(exp, act), 1):
        if a == b:
            continue
        if not (a.startswith(b"v ") and b.startswith(b"v ")):
            print("%s:%d: differs from %s" % (act_path, n, exp_path))
            return 1
        ta, tb = a.split(), b.split()
        if len(ta) != len(tb) or ta[4:] != tb[4:]:
            print("%s:%d: tokens differ" % (act_path, n))
            return 1
        d = math.sqrt(sum((float(x) - float(y)) ** 2 for x, y in zip(ta[1:4], tb[1:4])))
        worst = max(worst, d / diag)
        if not d <= tol * diag:
            print("%s:%d: vertex moved by %.3g of the diagonal (tolerance %g)" % (act_path, n, d / diag, tol))
            return 1
    print("%s: matches (max deviation %.3g of the diagonal)" % (act_path, worst))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
