"""One Python-module case: the command line's generators (cli_case.build) handed to
skinslide.Slider in a subprocess (py_worker.py), with argument forms only the module has (lists,
int32 arrays, a face table, float32 and Fortran-ordered frames, duplicate and negative ids, an
option of the other method), and the same invariants on what comes back."""
import json
import math
import os
import random
import subprocess
import time

import numpy as np

import cli_case
from cli_case import Slid, check_slide, movers, _patch_triangles, _expected_patch_moves
from meshio import Glb, Obj, weld

HERE = os.path.dirname(os.path.abspath(__file__))

PY_OPTIONS = {"--rotation-fits": ("rotation_fits", int), "--max-iterations": ("max_iterations", int),
              "--tolerance": ("tolerance", float), "--density": ("density", str),
              "--holes": ("holes", str), "--q-floor": ("q_floor", float),
              "--frame-solver": ("frame_solver", str), "--cg-tolerance": ("cg_tolerance", float),
              "--cg-max-iterations": ("cg_max_iterations", int), "--locate": ("locate", str),
              "--lookup-size": ("lookup_size", int), "--blend": ("blend", float),
              "--ease-in": ("ease_in", int), "--solver": ("solver", str),
              "--passes": ("passes", int)}


_read = {}


def _frame_positions(case, f):
    if f.positions is not None:
        return np.asarray(f.positions, dtype=np.float64)
    if f.source not in _read:
        if f.format == "obj":
            _read[f.source] = Obj.read(f.source).positions
        else:
            _read[f.source] = weld(Glb.read(f.source).raw)[0]
    return _read[f.source]


def build(seed, meshes, ctx):
    case = cli_case.build(seed, meshes, ctx)
    case.require_converged = False  # a command-line option: the module's runs compare with exit 0
    # --window: the module's slide_sequence over the same frames in the command's order (FRAME
    # files by number, a cache's samples); a clip's frames are the module's own, slid one by one.
    if case.mode == "animation":
        case.window = 0
        case.window_cycle = False
    rng = random.Random(seed ^ 0x5EED)
    case.py_usage = None
    case.py_input = None
    opts = {}
    k = 0
    while k < len(case.options):
        name, kind = PY_OPTIONS[case.options[k]]
        if not (name == "lookup_size" and case.method == "elastic"):
            opts[name] = kind(case.options[k + 1])
        k += 2
    if rng.random() < 0.05:
        other = {"elastic": ("q_floor", 0.01), "paper": ("rotation_fits", 2)}[case.method]
        opts[other[0]] = other[1]
        case.py_usage = f"{other[0]} belongs to the other method"
    case.py_options = opts
    case.faces_form = rng.choice(["flat", "lists"] + (["table"] if all(
        len(f) == 3 for f in case.mesh.faces) else []))
    case.flat_form = rng.choice(["int64", "int32"])
    case.patch_form = rng.choice(["list", "int64", "int32"])
    case.single_patch = len(case.selections) == 1 and rng.random() < 0.5
    case.py_selections = [list(s) for s in case.selections]
    if case.py_selections and case.py_selections[0] and rng.random() < 0.1:
        s = case.py_selections[0]
        s += rng.sample(s, min(len(s), 3))  # duplicates: the module takes each face once
        rng.shuffle(s)
    if case.py_selections and rng.random() < 0.04:
        case.py_selections[-1].append(rng.choice([-1, len(case.mesh.faces)]))
        case.py_input = "a face id out of range"
    if case.pins is not None and rng.random() < 0.04:
        case.pins = case.pins + [len(case.mesh.positions)]
    case.frame_form = rng.choice(["float64", "float64", "float32", "fortran", "strided"])
    case.edge_spread = rng.random() < 0.6
    case.pool = rng.random() < 0.2
    if case.mode == "animation":
        from cases import random_frame
        for n in range(rng.randint(1, 3)):
            p, deg, note = random_frame(rng, case.mesh.positions)
            case.frames.append(cli_case.Frame(n, p, "obj", note, deg))
    case.py_frames = []
    for f in case.frames:
        if f.bad:
            continue
        p = _frame_positions(case, f)
        if case.mode in ("pc2", "mdd") or f.format in ("glb", "gltf"):
            p = p.astype(np.float32).astype(np.float64)
        if case.frame_form == "float32":
            p = p.astype(np.float32).astype(np.float64)
        case.py_frames.append((f, p))
    if case.window and case.mode == "files":
        case.py_frames.sort(key=lambda fp: fp[0].number)
    # one malformed argument, in a case that is otherwise accepted, and the kind it must raise
    case.mangle = None
    if expected(case)[0] is None and case.py_frames and rng.random() < 0.15:
        case.mangle = rng.choice(list(MANGLES))
    return case


MANGLES = {  # name: (error kind, what)
    "degenerate_face_unselected": (None, "a face a, a, b outside the patches"),
    "degenerate_face_selected": ("input", "a selected face a, a, b"),
    "two_corner_face": ("input", "a face of 2 corners"),
    "nan_bind": ("input", "a NaN bind coordinate"),
    "nan_frame": ("input", "a NaN frame coordinate"),
    "short_frame": ("input", "a frame one vertex short"),
    "weight_above_one": ("usage", "a slide weight of 1.5"),
    "negative_strength": ("usage", "strength -1"),
    "nan_strength": ("usage", "strength NaN"),
}


def expected(case):
    """The error kind the case must raise (None: none; "maybe": input or numeric allowed), in
    the order skinslide checks: options, face ids, pins, the selection's topology."""
    if getattr(case, "mangle", None):
        kind, what = MANGLES[case.mangle]
        if kind:
            return kind, what
    if case.py_usage:
        return "usage", case.py_usage
    if case.py_input:
        return "input", case.py_input
    if case.empty_file:
        return "input", "an empty patch"
    if case.pins is not None and any(v >= len(case.mesh.positions) for v in case.pins):
        return "usage", "a pin out of range"
    if case.refusal:
        return "input", f"refusal: {case.refusal}"
    if case.corners_usage:
        return "usage", case.corners_usage
    short = cli_case.paper_short_outer(case)
    if short:
        return "input", "paper: an outer loop of 3 vertices"
    if short is None:
        return "maybe", "paper: an outer loop of 3 vertices may be chosen"
    if case.mesh.degenerate or any(f.degenerate for f, _ in case.py_frames):
        return "maybe", "degenerate geometry"
    if case.method == "elastic" and case.whole_component:
        return "maybe", "elastic on a whole component (a chart that may squeeze triangles to nothing)"
    return None, "a valid selection on good geometry"


def run_case(seed, meshes, ctx, folder):
    case = build(seed, meshes, ctx)
    mesh = case.mesh
    arrays = {"bind": mesh.positions}
    flat = np.array([v for f in mesh.faces for v in f], dtype=np.int64)
    arrays["face_vertices"] = flat
    arrays["face_sizes"] = np.array([len(f) for f in mesh.faces], dtype=np.int64)
    if case.faces_form == "table":
        arrays["face_table"] = flat.reshape(-1, 3)
    for i, s in enumerate(case.py_selections):
        arrays[f"patch{i}"] = np.array(s, dtype=np.int64)
    if case.pins is not None:
        arrays["pins"] = np.array(case.pins, dtype=np.int64)
    if case.weights is not None:
        arrays["weights"] = case.weights
    for k, (_, p) in enumerate(case.py_frames):
        arrays[f"frame{k}"] = p
    np.savez(folder / "spec.npz", **arrays)
    spec = {"faces": case.faces_form, "faces_form": case.flat_form, "patch_form": case.patch_form,
            "patch_count": len(case.py_selections), "single_patch": case.single_patch,
            "pins": case.pins is not None, "weights": case.weights is not None,
            "strength": case.strength, "outer": case.outer, "corners": case.corners,
            "method": case.method, "threads": case.threads, "options": case.py_options,
            "frame_count": len(case.py_frames), "frame_form": case.frame_form,
            "edge_spread": case.edge_spread, "pool": case.pool, "mangle": case.mangle,
            "window": case.window,
            "window_ends": "cycle" if getattr(case, "window_cycle", False) else "one-sided"}
    (folder / "spec.json").write_text(json.dumps(spec, indent=1))
    argv = ["/usr/bin/python3", os.path.join(HERE, "py_worker.py"), "spec.json"]
    env = dict(os.environ)
    env["PYTHONPATH"] = ctx.python_dir
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    preload = os.environ.get("SKINSLIDE_PROPERTY_PRELOAD")
    if preload:
        env["LD_PRELOAD"] = preload
        env["ASAN_OPTIONS"] = "detect_leaks=0:abort_on_error=1"
    t0 = time.monotonic()
    try:
        done = subprocess.run(argv, cwd=folder, capture_output=True, timeout=ctx.timeout, env=env)
        r = cli_case.Run(done.returncode, done.stdout.decode(errors="replace"),
                         done.stderr.decode(errors="replace"), time.monotonic() - t0)
    except subprocess.TimeoutExpired:
        r = cli_case.Run(None, "", "", time.monotonic() - t0, True)
    failures = cli_case.process_failures(r, "the Python interpreter")
    if r.code != 0 and not r.timed_out and r.code is not None and r.code > 0:
        failures.append(f"the interpreter exited {r.code}: {r.stderr.strip()[-600:]}")
    if failures:
        return case, argv, r.code, failures
    try:
        result = json.loads((folder / "result.json").read_text(), parse_constant=_no_constant)
    except (OSError, ValueError) as e:
        return case, argv, r.code, [f"result.json: {e}"]
    outs = np.load(folder / "result.npz")
    failures += check(case, result, outs)
    if not failures and not result.get("error") and _same_as_command(case):
        failures += _against_command(case, ctx, folder, outs)
    code = "error " + result["error"]["kind"] if result.get("error") else 0
    return case, argv, code, failures


def _same_as_command(case):
    """Cases whose every input the command line takes as the module did (not --no-slide: the
    command then copies the frames, and the module has no such mode)."""
    return (case.mode == "files" and not case.no_slide and case.mangle is None and
            case.frame_form != "float32" and
            case.usage_error is None and case.clash is None and
            all(f.format == "obj" and not f.bad for f in case.frames) and case.frames and
            expected(case)[0] is None)


def _against_command(case, ctx, folder, outs):
    """The module's positions against the command's on the same inputs, to the bit
    (lib/python/README.md)."""
    sub = folder / "command"
    args = cli_case.write(case, sub)
    r = cli_case.run(ctx.binary, args, sub, ctx.timeout)
    if r.code != 0:
        return [f"the command line on the same inputs exited {r.code}: {r.stderr.strip()[-300:]}"]
    problems = []
    for k, (f, _) in enumerate(case.py_frames):
        path = sub / "out" / f.name
        if not path.exists():
            continue  # not selected by --frames
        cli = Obj.read(path).positions
        if cli.tobytes() != outs[f"out{k}"].tobytes():
            n = int(np.any(cli != outs[f"out{k}"], axis=1).sum())
            problems.append(f"frame {k}: the module and the command differ at {n} vertices "
                            f"(command: {cli_case.shell_words([ctx.binary] + args)} in {sub})")
    return problems


def _no_constant(name):
    raise ValueError(f"non-finite number {name} in the module's report")


def check(case, result, outs):
    want, why = expected(case)
    err = result.get("error")
    if err:
        if err["kind"] is None:
            return [f"{err['type']} (not a skinslide.Error) at {result['stage']}: {err['message']}"]
        if err["kind"] == "internal":
            return [f"InternalError at {result['stage']}: {err['message']}"]
        if want is None:
            return [f"{err['type']} at {result['stage']}, expected success ({why}): {err['message']}"]
        if want != "maybe" and err["kind"] != want:
            return [f"{err['type']} ({err['kind']}), expected kind {want} ({why}): {err['message']}"]
        if want == "maybe" and err["kind"] not in ("input", "numeric"):
            return [f"{err['type']} ({err['kind']}) on degenerate geometry: {err['message']}"]
        return []
    if want not in (None, "maybe"):
        return [f"no error, expected kind {want} ({why})"]
    problems = []
    patches = result.get("patches", [])
    if len(patches) != len(case.comps):
        problems.append(f"slider.patches has {len(patches)} entries, expected {len(case.comps)}")
    else:
        for ci, p in enumerate(patches):
            free, moving = _expected_patch_moves(case, ci)
            got = (p.get("faces"), p.get("free"), p.get("skipped"))
            exp = (len(case.comps[ci].faces), len(free), not free)
            if got != exp:
                problems.append(f"slider.patches[{ci}] (faces, free, skipped) {got}, expected {exp}")
    may_move = movers(case)
    tris = _patch_triangles(case)
    for k, ((f, p), rep) in enumerate(zip(case.py_frames, result.get("reports", []))):
        out = outs[f"out{k}"]
        label = f"frame {k} ({f.note})"
        if out.shape != p.shape or out.dtype != np.float64:
            problems.append(f"{label}: slide returned {out.dtype} {out.shape}")
            continue
        changed = np.any(out.view(np.uint64) != p.view(np.uint64), axis=1)
        pair = Slid(label, p, out, changed, False)
        problems += check_slide(case, pair, may_move, tris,
                                identity=np.array_equal(p, case.mesh.positions) and (
                                    case.method == "elastic" or not case.mesh.degenerate))
        want_moved = 0
        mx = 0.0
        frame64 = p.astype(np.float64)
        for ci in range(len(case.comps)):
            free, moving = _expected_patch_moves(case, ci)
            rest = cli_case.at_rest(case, ci, frame64)
            reported = rep.get("patches", [])
            if ci < len(reported) and "at_rest" in reported[ci] and \
                    bool(reported[ci]["at_rest"]) != rest:
                problems.append(f"{label}: patch {ci} at_rest {reported[ci]['at_rest']!r}, the "
                                f"frame says {rest}")
            if free and not rest:
                want_moved += len(moving)
                if moving:
                    mx = max(mx, float(np.linalg.norm(out[moving] - p[moving], axis=1).max()))
        if rep.get("moved") != want_moved:
            problems.append(f"{label}: report moved {rep.get('moved')}, expected {want_moved}")
        ms = rep.get("max_slide")
        if not isinstance(ms, (int, float)) or abs(ms - mx) > 1e-12 * max(mx, 1e-300):
            problems.append(f"{label}: report max_slide {ms!r}, the positions say {mx!r}")
        for ci, pr in enumerate(rep.get("patches", [])):
            if case.edge_spread and not all(
                    isinstance(pr.get(key), (int, float)) and math.isfinite(pr[key])
                    for key in ("spread_frame", "spread_slid")):
                problems.append(f"{label}: patch {ci} spreads {pr.get('spread_frame')!r}, "
                                f"{pr.get('spread_slid')!r}")
            if case.method == "elastic" and cli_case.stop_problem(pr.get("stop")):
                problems.append(f"{label}: patch {ci} {cli_case.stop_problem(pr.get('stop'))}")
            # The search's fold-freedom (cli_case: the map counts its flips, promises none).
            if case.method == "elastic" and pr.get("flips") and ci < len(case.comps) and \
                    cli_case.searches(case):
                moving = _expected_patch_moves(case, ci)[1]
                if not any(0 < case.w_eff[v] < 1 for v in moving):
                    problems.append(f"{label}: patch {ci}: {pr['flips']} flips (elastic slides "
                                    f"fold-free)")
    if case.pool and result.get("pool_same") is False:
        problems.append("frames slid by a thread pool (slide_sequence: 3 threads) differ from the "
                        "serial bits")
    return problems


def describe(case):
    return (cli_case.describe(case) + f"\n  python: faces {case.faces_form}/{case.flat_form}, "
            f"patches {case.patch_form}{' (one list)' if case.single_patch else ''}, frames "
            f"{case.frame_form}, options {case.py_options}, edge_spread {case.edge_spread}, "
            f"pool {case.pool}, mangled {case.mangle}"
            f"{', slide_sequence window %d' % case.window if case.window else ''}"
            f"{' cycle' if getattr(case, 'window_cycle', False) else ''}; "
            f"expected {expected(case)[1]}")
