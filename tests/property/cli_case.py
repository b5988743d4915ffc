"""One command-line case: built from a seed (cases.py), written into a folder, run, checked.

build(seed, meshes, ctx) -> Case;  case.write(folder) -> argv;  check(case, folder, run) -> the
failures, each a sentence naming what broke."""
import json
import math
import os
import pathlib
import random
import re
import subprocess

import numpy as np

from cases import _pick, random_frame, random_selections, selection_text
from geometry import diagonal, distances_to_triangles, exact_within, fan_triangles
from meshio import FormatError, Glb, Obj, read_exr, read_mdd, read_pc2, read_png, weld, \
    write_mdd, write_pc2
from topology import Refusal, patch_components

# Elastic's per-patch `stop` says why a patch's last round ended. The names grow with the method
# (lib/elastic/README.md), so any short lowercase name is taken; "converged" is one of them.
STOP_NAME = re.compile(r"[a-z][a-z0-9 _-]{0,39}\Z")
ON_SURFACE = 1e-9  # of the frame's bounding-box diagonal (README "What it does": every slid vertex on a frame triangle)
F32 = 2.0 ** -24   # float32 rounding, relative


class Frame:
    """One frame as the case hands it in: welded positions (float64) and how it is stored."""

    def __init__(self, number, positions, fmt, note, degenerate=False):
        self.number, self.positions, self.format, self.note = number, positions, fmt, note
        self.degenerate = degenerate
        self.source = None      # an existing file to link instead of writing one
        self.bad = None         # "nan" / "short": a broken file, refused with exit 3
        self.name = None


class Case:
    pass


# ---- building -----------------------------------------------------------------------------------

def _frame_numbers(rng, n):
    start = rng.choice([0, 1, 1, 7, 100, 1001])
    step = rng.choice([1, 1, 1, 2, 5])
    return [start + k * step for k in range(n)]


def _frames_option(rng, numbers):
    """A --frames value over these numbers (sometimes selecting none)."""
    lo, hi = min(numbers), max(numbers)
    terms = []
    for _ in range(_pick(rng, [(1, 75), (2, 20), (3, 5)])):
        kind = rng.random()
        a = rng.randint(max(0, lo - 2), hi)
        if kind < 0.25:
            terms.append(str(a))
        else:
            b = rng.randint(a, hi + 5)
            sep = rng.choice([":", "x"])
            terms.append(f"{a}-{b}" + (f"{sep}{rng.randint(1, 3)}" if rng.random() < 0.3 else ""))
    return ",".join(terms)


def _selected(spec, numbers):
    chosen = []
    for k, n in enumerate(numbers):
        for term in spec.split(","):
            step = 1
            m = re.match(r"^(\d+)(?:-(\d+))?(?:[:x](\d+))?$", term.strip())
            a = int(m.group(1))
            b = int(m.group(2)) if m.group(2) else a
            if m.group(3):
                step = int(m.group(3))
            if a <= n <= b and (n - a) % step == 0:
                chosen.append(k)
                break
    return chosen


def build(seed, meshes, ctx):
    rng = random.Random(seed)
    case = Case()
    case.seed = seed
    case.notes = []
    weights = [(m, 2 if m.heavy else 2 if m.path.startswith(str(ctx.work)) else 6)
               for m in meshes]
    mesh = _pick(rng, weights).load()
    case.mesh = mesh
    case.notes.append(f"mesh {mesh.name}")
    cap = 1500 if mesh.heavy else 4000
    if ctx.sanitized:
        cap //= 4
    if mesh.heavy and rng.random() < 0.05 and not ctx.sanitized:
        cap = 12000
    nv = len(mesh.positions)

    # --- selection and what skinslide must make of it
    case.selections, sel_notes = random_selections(rng, mesh, cap)
    case.notes += [f"patch file {i}: {n}" for i, n in enumerate(sel_notes)]
    # A whole closed-ish component's chart can squeeze triangles below double precision's area
    # (README Limits: cut it into patches): elastic may refuse it, exit 5, naming the chart.
    case.whole_component = any(n.startswith(("a whole component", "the whole mesh")) or
                               "+ a whole component" in n or "+ the whole mesh" in n
                               for n in sel_notes)
    case.refusal = None
    case.comps = []
    case.empty_file = any(not s for s in case.selections)
    if case.empty_file:
        case.refusal = "a patch file selects no faces"
    else:
        try:
            case.comps = patch_components(mesh.faces, case.selections)
        except Refusal as r:
            case.refusal = str(r)
    case.patch_texts = [selection_text(rng, s) for s in case.selections]

    # --- method, options, controls
    case.method = rng.choice(["elastic", "paper"])
    opts = []
    big = sum(len(c.interior) for c in case.comps) > 2000
    if case.method == "elastic":
        if rng.random() < 0.3:
            opts += ["--rotation-fits", str(rng.choice([1, 2, 3, 5] if big else [1, 2, 3, 5, 10]))]
        if rng.random() < 0.3:
            opts += ["--max-iterations", str(rng.choice([0, 1, 2, 5, 20] if big else [0, 1, 5, 20, 100]))]
        if rng.random() < 0.3:
            opts += ["--tolerance", rng.choice(["0", "1e-6", "3e-4", "0.01", "1"] if not big
                                               else ["1e-6", "3e-4", "0.01", "1"])]
        if rng.random() < 0.3:
            opts += ["--blend", rng.choice(["0", "0.3", "1", "2"])]
        fits = int(opts[opts.index("--rotation-fits") + 1]) if "--rotation-fits" in opts else 3
        if fits > 1 and rng.random() < 0.2:
            opts += ["--ease-in", str(rng.randrange(1, fits))]
        if opts:  # the search's internals: --solver search (lib/elastic/README.md)
            opts += ["--solver", "search"]
        elif rng.random() < 0.3:
            opts += ["--passes", str(rng.choice([1, 2, 3, 8]))]
    else:
        if rng.random() < 0.3:
            opts += ["--density", rng.choice(["paper", "inverse", "length", "uniform"])]
        if rng.random() < 0.3:
            opts += ["--holes", rng.choice(["free", "fill"])]
        if rng.random() < 0.2:
            opts += ["--q-floor", rng.choice(["1e-12", "1e-6", "1e-3", "0.1", "1"])]
        if rng.random() < 0.3:
            opts += ["--frame-solver", rng.choice(["auto", "cholesky", "multigrid", "cg"])]
        if rng.random() < 0.2:
            opts += ["--cg-tolerance", rng.choice(["1e-16", "1e-12", "1e-6", "1e-2"])]
        if rng.random() < 0.2:
            opts += ["--cg-max-iterations", str(rng.choice([1, 5, 50, 2000]))]
        if rng.random() < 0.3:
            opts += ["--locate", rng.choice(["walk", "image"])]
    case.dump = rng.random() < 0.2 and not (mesh.heavy and cap > 2000)
    if rng.random() < 0.3 or case.dump:
        # the dumps' resolution (and --locate image's): small, to stay fast
        opts += ["--lookup-size", str(rng.choice([8, 16, 64, 128]))]
    case.options = opts

    case.pins = None
    if rng.random() < 0.3:
        pool = list(range(nv))
        inner = [v for c in case.comps for v in c.interior]
        border = [v for c in case.comps for v in c.boundary]
        pins = set()
        for _ in range(rng.randint(1, 12)):
            src = _pick(rng, [(inner or pool, 6), (border or pool, 2), (pool, 2)])
            pins.add(rng.choice(src))
        case.pins = sorted(pins)
        case.pin_text = selection_text(rng, pins, prefix="vtx")
    case.weights = None
    case.weight_file = None
    case.colour_channel = None
    if rng.random() < 0.3:
        if mesh.colours and rng.random() < 0.4:
            case.colour_channel = rng.choice("rgb")
            case.weights = _obj_colours(mesh)[:, "rgb".index(case.colour_channel)]
        else:
            w = np.array([_pick(rng, [(0.0, 2), (1.0, 3), (None, 5)]) for _ in range(nv)], dtype=object)
            w = np.array([rng.random() if x is None else x for x in w], dtype=float)
            if rng.random() < 0.5:
                case.weight_file = "# dense\n" + "".join(f"{x!r}\n" for x in w)
            else:
                listed = [v for v in range(nv) if w[v] > 0 or rng.random() < 0.1]
                w2 = np.zeros(nv)
                w2[listed] = w[listed]
                w = w2
                case.weight_file = "# sparse\n" + "".join(f"{v} {w[v]!r}\n" for v in listed)
            case.weights = w
    case.strength = None
    if rng.random() < 0.25:
        case.strength = rng.choice([0.0, 0.3, 0.5, 1.0, 1.7, 1e6])
    w = np.ones(nv) if case.weights is None else case.weights.copy()
    s = 1.0 if case.strength is None else case.strength
    case.w_eff = np.clip(w * s, 0.0, 1.0)

    case.outer = []
    case.corners = []
    case.corners_usage = None
    valid = [c for c in case.comps if c.interior]
    if valid and rng.random() < 0.15:
        c = rng.choice(valid)
        case.outer.append(rng.choice(sorted(c.boundary)))
    if valid and case.method == "paper" and rng.random() < 0.1:
        c = rng.choice(valid)
        loop = rng.choice(c.loops)
        if len(loop) >= 4 and not case.outer:
            idx = sorted(rng.sample(range(len(loop)), 4))
            q = [loop[i] for i in idx]
            case.corners.append(q)
            # a loop two patches share serves both, and they walk it in opposite directions
            # (a patch with nothing free is skipped, never set up: it does not walk it)
            pins = set(case.pins or [])
            for other in case.comps:
                if not [v for v in other.interior if v not in pins]:
                    continue
                for lp in other.loops:
                    if all(v in lp for v in q):
                        at = [lp.index(v) for v in q]
                        n = len(lp)
                        if sorted(at, key=lambda a: (a - at[0]) % n) != at:
                            case.corners_usage = "--corners on a loop two patches walk " \
                                                 "in opposite directions"

    # --- frames
    case.mode = "files"
    if mesh.kind == "glb" and rng.random() < 0.4:
        case.mode = "animation"
    elif rng.random() < 0.12:
        case.mode = rng.choice(["pc2", "mdd"])
    case.frames = []
    case.usage_error = None
    if case.mode == "animation":
        case.clip = rng.randrange(mesh.clips)
        case.fps = rng.choice([None, None, 5, 24])
        case.format = rng.choice(["glb", "obj", "pc2"])
        case.frames_spec = None
        if rng.random() < 0.7:
            a = rng.randint(0, 20)
            case.frames_spec = f"{a}-{a + rng.randint(0, 3)}"
    else:
        count = _pick(rng, [(1, 30), (2, 30), (3, 25), (5, 15)])
        if mesh.heavy:
            count = min(count, 2)
        numbers = _frame_numbers(rng, count)
        for n in numbers:
            fr = _make_frame(rng, mesh, n, case.mode, ctx)
            case.frames.append(fr)
        case.frames_spec = None
        if rng.random() < 0.15:
            case.frames_spec = _frames_option(rng, numbers)
            chosen = _selected(case.frames_spec, numbers)
            if not chosen:
                case.usage_error = "--frames selects no frame"
            elif case.mode in ("pc2", "mdd") and chosen != list(range(chosen[0], chosen[-1] + 1)):
                case.usage_error = "--frames selects samples with gaps"
        if case.mode == "mdd":
            for k, fr in enumerate(case.frames):
                fr.number = k
            if case.frames_spec:
                chosen = _selected(case.frames_spec, list(range(count)))
                case.usage_error = None if chosen and chosen == list(
                    range(chosen[0], chosen[-1] + 1)) else "--frames selects nothing or gaps"
        written = [f for f in case.frames if f.format == "obj" and f.source is None]
        if case.mode == "files" and written and rng.random() < 0.05:
            rng.choice(written).bad = rng.choice(["nan", "short"])
    case.cache_obj = case.mode in ("pc2", "mdd") and mesh.kind == "obj" and rng.random() < 0.3
    if case.cache_obj and case.usage_error in ("--frames selects samples with gaps",
                                                "--frames selects nothing or gaps") and \
            _selected(case.frames_spec, [f.number for f in case.frames]):
        case.usage_error = None  # a file a frame: a cache's gaps do not matter
    # --no-slide: every frame read, checked and written unchanged (no bind set-up)
    case.no_slide = rng.random() < 0.04
    # outputs that would overwrite inputs or each other: refused before any work (exit 2)
    case.clash = None
    if case.mode == "files" and rng.random() < 0.04:
        case.clash = rng.choice(["twice", "into_frames"])
    case.threads = rng.choice([1, 1, 2])
    case.report = rng.random() < 0.6
    case.no_timings = case.report and rng.random() < 0.3
    case.preview = rng.random() < 0.2
    case.preview_size = rng.choice([16, 32, 64])
    if case.no_slide and rng.random() < 0.8:
        case.report = case.no_timings = case.dump = case.preview = False
    case.keep_going = rng.random() < 0.3
    case.verbosity = rng.choice(["-q", "", "-v"])
    case.config = rng.random() < 0.1
    # --require-converged (elastic): a patch that did not converge fails its frame with exit 5.
    # Only where this build has it (ctx.options: its --help), and from a stream of its own, so
    # the rest of each case is the same with or without the option.
    case.require_converged = (case.method == "elastic" and not case.no_slide and
                              "--require-converged" in ctx.options and
                              random.Random(seed ^ 0xC0417).random() < 0.25)
    # --window N (elastic): each frame written with its neighbours' slides (README "Elastic"), a
    # frame's failure failing the windows that hold it. From streams of its own too.
    case.window = 0
    if case.method == "elastic" and not case.no_slide and "--window" in ctx.options and \
            random.Random(seed ^ 0x3A1D0).random() < 0.2:
        case.window = random.Random(seed ^ 0x3A1D1).choice([1, 2, 4])
    # --window-ends cycle (a loop: the windows wrap around the sequence's ends) in a third of them
    case.window_cycle = bool(case.window) and "--window-ends" in ctx.options and \
        random.Random(seed ^ 0x3A1D2).random() < 1 / 3
    return case


def stop_problem(stop):
    """None for a stop name the report may give, else what is wrong with it."""
    if not isinstance(stop, str) or not STOP_NAME.match(stop):
        return f"stop {stop!r} (a short lowercase name expected)"
    return None


def _obj_colours(mesh):
    if hasattr(mesh, "obj_colours"):
        return mesh.obj_colours
    rows = []
    for i in mesh.obj.v_lines:
        tok = mesh.obj.lines[i].split()
        rows.append([float(t) for t in tok[4:7]])
    mesh.obj_colours = np.array(rows)
    return mesh.obj_colours


_own_positions = {}


def _make_frame(rng, mesh, number, mode, ctx):
    own = mesh.own_frames
    if own and rng.random() < 0.35:
        path = rng.choice(own)
        if mode in ("pc2", "mdd"):
            if path not in _own_positions:
                _own_positions[path] = Obj.read(path).positions
            return Frame(number, _own_positions[path], mode, f"own frame {os.path.basename(path)}")
        fr = Frame(number, None, "obj", f"own frame {os.path.basename(path)}")
        fr.source = path
        return fr
    if mesh.kind == "glb" and mode == "files" and rng.random() < 0.3:
        posed = ctx.posed(mesh, rng)
        if posed:
            fr = Frame(number, None, "glb", f"posed {os.path.basename(posed)}")
            fr.source = posed
            return fr
    positions, degenerate, note = random_frame(rng, mesh.positions)
    fmt = "obj" if mode != "files" or mesh.kind == "obj" else rng.choice(["obj", "glb", "gltf"])
    if mode in ("pc2", "mdd"):
        fmt = mode
    return Frame(number, positions, fmt, note, degenerate)


# ---- writing ------------------------------------------------------------------------------------

def _link(src, dst):
    dst = pathlib.Path(dst)
    if dst.exists() or dst.is_symlink():
        dst.unlink()
    os.symlink(os.path.abspath(src), dst)


def write(case, folder):
    """Writes the case's inputs into `folder` and returns the command's arguments (relative to
    `folder`). Loads each frame's positions as skinslide will read them."""
    folder = pathlib.Path(folder)
    (folder / "frames").mkdir(parents=True, exist_ok=True)
    mesh = case.mesh
    ext = ".obj" if mesh.kind == "obj" else ".glb"
    bind = f"bind{ext}"
    _link(mesh.path, folder / bind)
    args = []
    for i, text in enumerate(case.patch_texts):
        (folder / f"patch{i}.txt").write_text(text)
    cfg = []
    for i in range(len(case.patch_texts)):
        args += ["--patch", f"patch{i}.txt"]
    if case.pins is not None:
        (folder / "pins.txt").write_text(case.pin_text)
        args += ["--pin", "pins.txt"]
    if case.weight_file is not None:
        (folder / "weights.txt").write_text(case.weight_file)
        args += ["--weights", "weights.txt"]
    if case.colour_channel:
        args += ["--weights-from-obj-color", case.colour_channel]
    if case.strength is not None:
        args += ["--strength", repr(case.strength)]
    for v in case.outer:
        args += ["--outer-loop-vertex", str(v)]
    for q in case.corners:
        args += ["--corners", ",".join(map(str, q))]
    if case.method != "elastic" or random.Random(case.seed).random() < 0.3:
        args += ["--method", case.method]
    args += case.options
    if case.require_converged:
        args.append("--require-converged")
    if getattr(case, "window", 0):
        args += ["--window", str(case.window)]
    if getattr(case, "window_cycle", False):
        args += ["--window-ends", "cycle"]
    if case.config:
        # some options from a TOML file instead (README "Controls": --config); the command line
        # keeps the rest
        pairs, k = [], 0
        while k < len(args):
            if k + 1 < len(args) and not args[k + 1].startswith("--"):
                pairs.append((args[k], args[k + 1]))
                k += 2
            else:
                pairs.append((args[k], None))
                k += 1
        kept = []
        for flag, value in pairs:
            if flag in ("--strength", "--rotation-fits", "--max-iterations", "--q-floor",
                        "--cg-max-iterations", "--lookup-size", "--tolerance", "--cg-tolerance",
                        "--blend", "--ease-in"):
                cfg.append(f"{flag[2:]} = {value}")
            elif flag in ("--method", "--density", "--holes", "--frame-solver", "--locate"):
                cfg.append(f'{flag[2:]} = "{value}"')
            else:
                kept += [flag] + ([value] if value is not None else [])
        (folder / "config.toml").write_text("\n".join(cfg) + "\n")
        args = kept + ["--config", "config.toml"]
    args += ["-j", str(case.threads)]
    if case.no_slide:
        args.append("--no-slide")
    if case.verbosity:
        args.append(case.verbosity)
    if case.report:
        args += ["--report", "report.json"]
        if case.no_timings:
            args.append("--report-no-timings")
    if case.dump:
        args += ["--dump", "dump"]
    if case.preview:
        args += ["--preview", "preview", "--preview-size", str(case.preview_size)]
    if case.keep_going:
        args.append("--keep-going")
    args += ["-o", "frames" if case.clash == "into_frames" else "out"]
    if case.frames_spec:
        args += ["--frames", case.frames_spec]
    if case.mode == "animation":
        args += ["--animation", str(case.clip), "--format", case.format]
        if case.fps:
            args += ["--fps", str(case.fps)]
        args.append(bind)
        return args
    args.append(bind)
    if case.mode in ("pc2", "mdd"):
        samples = np.array([f.positions for f in case.frames])
        if case.mode == "pc2":
            n0 = case.frames[0].number
            rate = case.frames[1].number - n0 if len(case.frames) > 1 else 1
            write_pc2(folder / "frames/shot.pc2", samples, float(n0), float(rate))
        else:
            write_mdd(folder / "frames/shot.mdd", samples)
        for f in case.frames:
            f.positions = np.asarray(f.positions, dtype=np.float32).astype(np.float64)
        args.append(f"frames/shot.{case.mode}")
        if case.cache_obj:
            args[-1:-1] = ["--format", "obj"]
        return args
    stem = random.Random(case.seed + 1).choice(["fr", "shot_a", "arm"])
    for f in case.frames:
        f.name = f"{stem}.{f.number:04d}.{f.format}"
        path = folder / "frames" / f.name
        if f.source:
            _link(f.source, path)
            f.positions = None
        elif f.format == "obj":
            text = _obj_frame_text(mesh, f.positions)
            if f.bad == "nan":
                lines = text.split("\n")
                i = [k for k, l in enumerate(lines) if l.startswith("v ")][len(f.positions) // 2]
                lines[i] = "v nan 0 0"
                text = "\n".join(lines)
            elif f.bad == "short":
                lines = text.split("\n")
                i = [k for k, l in enumerate(lines) if l.startswith("v ")][-1]
                del lines[i]
                text = "\n".join(lines)
            path.write_text(text)
        elif f.format == "glb":
            raw = f.positions[mesh.raw_ids].astype(np.float32)
            path.write_bytes(mesh.glb.with_positions(raw))
        else:
            raw = f.positions[mesh.raw_ids].astype(np.float32)
            text, data = mesh.glb.to_gltf(raw, f"{stem}.{f.number:04d}.bin")
            path.write_text(text)
            (folder / "frames" / f"{stem}.{f.number:04d}.bin").write_bytes(data)
        args.append(f"frames/{f.name}")
    if case.clash == "twice":
        args.append(f"frames/{case.frames[0].name}")
    return args


def _obj_frame_text(mesh, positions):
    if mesh.kind == "obj":
        return mesh.obj.with_positions(positions)
    out = ["# frame written by tests/property"]
    out += ["v %r %r %r" % tuple(map(float, p)) for p in positions]
    out += ["f " + " ".join(str(v + 1) for v in f) for f in mesh.faces]
    return "\n".join(out) + "\n"


# ---- running ------------------------------------------------------------------------------------

class Run:
    def __init__(self, code, stdout, stderr, seconds, timed_out=False):
        self.code, self.stdout, self.stderr = code, stdout, stderr
        self.seconds, self.timed_out = seconds, timed_out


def run(binary, args, folder, timeout, env=None):
    import time
    t0 = time.monotonic()
    try:
        done = subprocess.run([binary] + args, cwd=folder, capture_output=True, timeout=timeout,
                              env=env)
        return Run(done.returncode, done.stdout.decode(errors="replace"),
                   done.stderr.decode(errors="replace"), time.monotonic() - t0)
    except subprocess.TimeoutExpired as e:
        return Run(None, (e.stdout or b"").decode(errors="replace"),
                   (e.stderr or b"").decode(errors="replace"), time.monotonic() - t0, True)


SANITIZER = re.compile(r"(AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer|"
                       r"runtime error:|ThreadSanitizer|MemorySanitizer)")


def process_failures(r, label="skinslide"):
    """What any run must honour: no hang, no signal, no internal error, a message with every
    non-zero exit, no sanitizer report, nothing on stdout."""
    out = []
    if r.timed_out:
        return [f"{label} did not finish within the case's time limit"]
    if r.code < 0:
        out.append(f"{label} was killed by signal {-r.code}")
    elif r.code not in (0, 2, 3, 4, 5):
        out.append(f"{label} exited {r.code} (not one of 0, 2, 3, 4, 5)")
    if r.code and r.code > 0 and "skinslide: error: " not in r.stderr:
        out.append(f"{label} exited {r.code} without a 'skinslide: error:' line")
    m = SANITIZER.search(r.stderr)
    if m:
        out.append(f"{label}: sanitizer report ({m.group(1)})")
    if r.stdout.strip():
        out.append(f"{label} wrote to stdout: {r.stdout[:200]!r}")
    return out


# ---- checking -----------------------------------------------------------------------------------

def paper_short_outer(case):
    """paper: a patch that slides needs an outer loop of at least 4 vertices (the square's
    corners). True: some patch's certainly has 3; None: a near tie makes it uncertain."""
    if case.method != "paper":
        return False
    chosen = set(case.outer) | {q[0] for q in case.corners}
    pins = set(case.pins or [])
    verdict = False
    for c in case.comps:
        if not [v for v in c.interior if v not in pins]:
            continue  # skipped: not set up
        picked = [lp for lp in c.loops if chosen & set(lp)]
        if picked:
            candidates = picked[:1]
        else:
            lengths = [sum(float(np.linalg.norm(case.mesh.positions[lp[k]] -
                                                case.mesh.positions[lp[k - 1]]))
                           for k in range(len(lp))) for lp in c.loops]
            top = max(lengths)
            candidates = [lp for lp, l in zip(c.loops, lengths) if l >= top * (1 - 1e-6)]
        short = [len(lp) < 4 for lp in candidates]
        if all(short):
            return True
        if any(short):
            verdict = None
    return verdict


def expected_codes(case):
    """The exit codes the case allows, and why."""
    if case.no_slide and (case.mode == "animation" or case.report or case.dump or case.preview):
        return {2}, "--no-slide with --animation, --report, --dump or --preview"
    if case.usage_error:
        return {2}, case.usage_error
    if case.clash:
        return {2}, "an output would overwrite an input or another output"
    if case.no_slide:
        if case.empty_file:
            return {3}, "--no-slide: an empty patch file"
        if any(f.bad for f in _selected_frames(case)) or \
                any(getattr(f, "weld_changed", False) for f in _selected_frames(case)):
            return {3}, "--no-slide: a broken frame"
        return {0}, "--no-slide: the frames copied (no bind set-up, no topology checks)"
    if case.refusal:
        return {3}, f"refusal: {case.refusal}"
    if case.corners_usage:
        return {2}, case.corners_usage
    short = paper_short_outer(case)
    if short:
        return {3}, "paper: a patch's outer loop has 3 vertices (the square needs 4 corners)"
    if short is None:
        return {0, 3}, "paper: an outer loop of 3 vertices may be chosen (a near tie)"
    codes, why = _geometry_codes(case)
    if any(f.bad for f in _read_frames(case)):
        # frames are slid in order: an earlier frame may fail first (--require-converged)
        return (codes - {0}) | {3}, "a broken frame file" + ("" if codes == {0} else f"; or {why}")
    if any(getattr(f, "weld_changed", False) for f in _read_frames(case)):
        # the frame is refused when read (exit 3); an earlier frame may fail first
        return (codes - {0}) | {3}, \
            "a glTF frame whose float32 positions weld differently from the bind" + \
            ("" if codes == {0} else f"; or {why}")
    return codes, why


def _geometry_codes(case):
    """The exit codes the method allows on the case's geometry and options, and why."""
    degenerate_bind = case.mesh.degenerate
    degenerate_frame = any(f.degenerate for f in case.frames)
    if case.method == "paper" and (degenerate_bind or degenerate_frame):
        return {0, 3, 5}, "paper on degenerate geometry (a singular or zero-length net)"
    if case.method == "elastic" and degenerate_bind:
        return {0, 5}, "elastic on a degenerate bind (a chart that cannot be built)"
    if case.method == "elastic" and case.whole_component:
        return {0, 5}, "elastic on a whole component (a chart that may squeeze triangles to nothing)"
    if getattr(case, "require_converged", False):
        return {0, 5}, "--require-converged: a patch that did not converge fails its frame"
    return {0}, "a valid selection on good geometry"


def unconverged_problems(case, stderr):
    """--require-converged's exit 5: each error line names the frame and the patch."""
    if not getattr(case, "require_converged", False):
        return []
    # A cache with failed samples is not written at all: that line names the cache, the
    # samples' own lines above it name frame and patch.
    errors = [ln for ln in stderr.splitlines() if "skinslide: error: " in ln]
    # A glTF frame that welds differently is refused when read (its own exit 3, beside the
    # others' 5 under --keep-going): its line names no patch.
    refused = [f.name for f in _selected_frames(case) if getattr(f, "weld_changed", False)]
    # A broken frame file is refused when read too (exit 3 under --keep-going, after an earlier
    # frame's 5): its line names the file and the line, no patch.
    broken = [f.name for f in _selected_frames(case) if f.bad]
    lines = [ln for ln in errors if "samples failed, and a cache cannot have holes" not in ln
             and not any(f"{n}: has " in ln for n in refused)
             and not any(n in ln for n in broken)]
    if not lines:
        # process_failures says so when nothing is said at all
        return [f"a cache refused with no sample named: {errors[0]!r}"] if errors else []
    names = [f.name for f in _selected_frames(case)] if case.mode == "files" else []
    bad = [ln for ln in lines if not re.search(r"\bpatch(es)? \d", ln) or
           (names and not any(n in ln for n in names))]
    if bad:
        return [f"exit 5 under --require-converged without the frame and the patch: {bad[0]!r}"]
    # a patch that moves nothing (no free vertex, all pinned or of weight 0) has nothing to
    # converge
    still = [int(m) for ln in lines for m in re.findall(r"\bpatch (\d+)", ln)
             if int(m) < len(case.comps) and not _expected_patch_moves(case, int(m))[1]]
    if still:
        return [f"exit 5 under --require-converged for patch {still[0]}, which moves no vertex"]
    return []


def _temporaries(folder):
    return [str(p.relative_to(folder)) for p in pathlib.Path(folder).rglob(".*.tmp.*")]


def check(case, folder, r, ref=None):
    folder = pathlib.Path(folder)
    failures = process_failures(r)
    if r.timed_out:
        return failures
    allowed, why = expected_codes(case)
    if r.code not in allowed:
        failures.append(f"exit {r.code}, expected {sorted(allowed)} ({why}); stderr: "
                        f"{_tail(r.stderr)}")
    tmp = _temporaries(folder)
    if tmp:
        failures.append(f"temporaries left behind: {tmp[:5]}")
    if r.code != 0:
        # --no-slide checks no patch but reads every patch file: a refusal of the patches does
        # not apply, an empty file does (before any frame), and a broken frame under
        # --keep-going leaves the good frames written
        refused = r.code == 3 and (
            (case.no_slide and case.empty_file) or
            (not case.no_slide and
             (case.refusal or case.usage_error or paper_short_outer(case) is not False)))
        if r.code == 2 or refused:
            written = [p for d in ("out", "dump", "preview") for p in (folder / d).rglob("*")
                       if p.is_file()] + ([folder / "report.json"]
                                           if (folder / "report.json").exists() else [])
            if written:
                failures.append(f"a refused run wrote {[str(p.relative_to(folder)) for p in written][:5]}")
        elif r.code > 0:
            if r.code == 5 and "--require-converged" in why:
                failures += unconverged_problems(case, r.stderr)
            try:
                failures += _check_partial(case, folder, r.stderr)
            except FormatError as e:
                failures.append(f"an output of a failed run does not parse: {e}")
        return failures
    if r.code == 0:
        try:
            failures += _check_outputs(case, folder, ref)
        except FormatError as e:
            failures.append(f"an output does not parse: {e}")
    return failures


VALUED = {"-j", "-o", "--report", "--dump", "--preview", "--preview-size", "--frames"}
FLAGS = {"--report-no-timings", "--keep-going"}


def rerun_args(case, args, rng):
    """The case's command again with the other thread count, into out2/, with a subset of the
    selected frames in reverse order, and no report, dumps or previews: README "No history"
    says each output must come back byte for byte."""
    kept, k = [], 0
    while k < len(args):
        a = args[k]
        if a in VALUED:
            k += 2
            continue
        if a not in FLAGS and not a.startswith("frames/"):
            kept.append(a)
        k += 1
    frames = [f for f in _selected_frames(case)]
    subset = [f for f in frames if rng.random() < 0.7] or frames[-1:]
    given = subset
    if getattr(case, "window", 0):
        # a window's neighbours are the frames given: every frame, the subset picked by --frames
        # (README "Farm")
        given = case.frames
        kept = kept[:-1] + ["--frames", ",".join(str(f.number) for f in subset)] + kept[-1:]
    return kept[:-1] + ["-j", "2" if case.threads == 1 else "1", "-o", "out2", kept[-1]] + \
        [f"frames/{f.name}" for f in reversed(given)], [f.name for f in subset]


def shell_words(args):
    import shlex
    return " ".join(shlex.quote(a) for a in args)


def _tail(text, n=600):
    text = text.strip()
    return text if len(text) <= n else "..." + text[-n:]


def _check_partial(case, folder, stderr=""):
    """A failed frame leaves no file; with --keep-going every good frame is written."""
    out = []
    if case.mode != "files":
        return out
    errors = [ln for ln in stderr.splitlines() if "skinslide: error: " in ln]
    for f in case.frames:
        path = folder / "out" / f.name
        if f.bad and path.exists():
            out.append(f"the broken frame {f.name} has an output")
        unconverged = getattr(case, "require_converged", False) and \
            any(f.name in ln for ln in errors)
        if unconverged and path.exists():
            out.append(f"{f.name} failed --require-converged and has an output")
        if case.keep_going and not f.bad and not f.degenerate and not unconverged and \
                not path.exists() and not case.frames_spec and \
                not any(g.bad or g.degenerate or getattr(g, "weld_changed", False)
                        for g in _window(case, f)):
            out.append(f"--keep-going: the good frame {f.name} has no output")
    # what was written is complete and slid as promised
    pairs, problems = _pairs(case, folder, None, partial=True)
    may_move = movers(case)
    tris = _patch_triangles(case)
    for pair in pairs:
        problems += check_slide(case, pair, may_move, tris)
    return out + problems


def _sequence(case):
    """The frames in the order --window takes them: FRAME files by number, samples by index."""
    if case.mode == "files":
        return sorted(case.frames, key=lambda f: f.number)
    return list(case.frames)


def _window(case, frame):
    """The frames within --window of `frame` in the sequence (itself alone without a window),
    around the loop with --window-ends cycle."""
    reach = getattr(case, "window", 0)
    seq = _sequence(case)
    at = next(k for k, f in enumerate(seq) if f is frame)
    if getattr(case, "window_cycle", False):
        return [seq[(at + k) % len(seq)] for k in range(-reach, reach + 1)]
    return seq[max(0, at - reach):at + reach + 1]


def _read_frames(case):
    """The frames a run reads: the selected ones and, with --window, their neighbours."""
    chosen = _selected_frames(case)
    if not getattr(case, "window", 0) or case.mode == "animation":
        return chosen
    held = {id(g) for f in chosen for g in _window(case, f)}
    return [f for f in case.frames if id(f) in held]


def _selected_frames(case):
    if case.mode == "mdd":
        numbers = list(range(len(case.frames)))
    else:
        numbers = [f.number for f in case.frames]
    chosen = _selected(case.frames_spec, numbers) if case.frames_spec else range(len(numbers))
    return [case.frames[k] for k in chosen]


class Slid:
    """One output and its frame, as welded arrays: positions, which vertices differ in bits from
    the frame, and the rounding the format adds."""

    def __init__(self, label, frame_pos, out_pos, changed, f32):
        self.label, self.frame, self.out, self.changed, self.f32 = \
            label, frame_pos, out_pos, changed, f32


def _obj_pair(label, frame_path, out_path, expect_lines=True):
    fobj, oobj = Obj.read(frame_path), Obj.read(out_path)
    problems = []
    if len(fobj.lines) != len(oobj.lines) or fobj.v_lines != oobj.v_lines:
        problems.append(f"{label}: the output has other lines than its frame")
        return None, problems
    vset = set(fobj.v_lines)
    for i, (a, b) in enumerate(zip(fobj.lines, oobj.lines)):
        if i not in vset and a != b:
            problems.append(f"{label}:{i + 1}: a line that is not a v line changed: {a!r} -> {b!r}")
            break
    changed = np.zeros(len(fobj.v_lines), dtype=bool)
    for v, i in enumerate(fobj.v_lines):
        a, b = fobj.lines[i], oobj.lines[i]
        if a != b:
            changed[v] = True
            ta, tb = a.split(), b.split()
            if ta[4:] != tb[4:]:
                problems.append(f"{label}:{i + 1}: the v line's fields past x y z changed")
            if not all(math.isfinite(float(t)) for t in tb[1:4]):
                problems.append(f"{label}:{i + 1}: non-finite coordinate {b!r}")
    # a rewritten line whose numbers are those of the frame is still unchanged
    same = np.all(fobj.positions == oobj.positions, axis=1)
    changed &= ~same
    return Slid(label, fobj.positions, oobj.positions, changed, False), problems


def _glb_pair(label, frame_path, out_path, raw_ids):
    fg, og = Glb.read(frame_path), Glb.read(out_path)
    problems = []
    if fg.raw.shape != og.raw.shape or not np.array_equal(fg.raw_triangles, og.raw_triangles):
        return None, [f"{label}: the output's vertices or triangles differ from its frame's"]
    if not np.all(np.isfinite(og.raw)):
        problems.append(f"{label}: non-finite POSITION")
    nw = raw_ids.max() + 1
    fpos = np.zeros((nw, 3))
    fpos[raw_ids] = fg.raw
    opos = np.zeros((nw, 3))
    opos[raw_ids] = og.raw
    if not np.array_equal(opos[raw_ids], og.raw):
        problems.append(f"{label}: raw copies of one welded vertex were written apart")
    bits_f = fg.raw.astype(np.float32).view(np.uint32)
    bits_o = og.raw.astype(np.float32).view(np.uint32)
    raw_changed = np.any(bits_f != bits_o, axis=1)
    changed = np.zeros(nw, dtype=bool)
    np.logical_or.at(changed, raw_ids, raw_changed)
    for prim in og.json["meshes"][0]["primitives"]:
        if "NORMAL" in prim.get("attributes", {}):
            n = og.accessor(prim["attributes"]["NORMAL"]).astype(np.float64)
            if not np.all(np.isfinite(n)):
                problems.append(f"{label}: non-finite NORMAL")
    return Slid(label, fpos, opos, changed, True), problems


def _cache_obj_pairs(case, folder):
    """A cache slid into a file a frame (--format obj): the bind's own text at each sample."""
    frames = _selected_frames(case)
    names = sorted(p.name for p in (folder / "out").iterdir())
    want = {f"shot.{f.number:04d}.obj": f for f in frames}
    if names != sorted(want):
        return [], [f"--format obj from a cache wrote {names[:5]}, expected {sorted(want)[:5]}"]
    bind = case.mesh.obj
    pairs, problems = [], []
    for name, f in want.items():
        out = Obj.read(folder / "out" / name)
        if len(out.lines) != len(bind.lines) or out.v_lines != bind.v_lines:
            problems.append(f"{name}: not the bind's lines")
            continue
        vset = set(bind.v_lines)
        for i, (a, b) in enumerate(zip(bind.lines, out.lines)):
            if i not in vset and a != b:
                problems.append(f"{name}:{i + 1}: the bind's line {a!r} written as {b!r}")
                break
        frame = np.asarray(f.positions, dtype=np.float32).astype(np.float64)
        changed = np.any(out.positions != frame, axis=1)
        pairs.append(Slid(name, frame, out.positions, changed, False))
    return pairs, problems


def _cache_pairs(case, folder):
    if case.cache_obj:
        return _cache_obj_pairs(case, folder)
    outs = sorted(p for p in (folder / "out").iterdir())
    if len(outs) != 1:
        return [], [f"a cache run wrote {len(outs)} files: {[p.name for p in outs]}"]
    reader = read_pc2 if case.mode == "pc2" else read_mdd
    data = reader(outs[0])
    frames = _selected_frames(case)
    if len(data["samples"]) != len(frames):
        return [], [f"{outs[0].name}: {len(data['samples'])} samples, {len(frames)} selected"]
    pairs = []
    for k, f in enumerate(frames):
        out = data["samples"][k].astype(np.float64)
        fr32 = np.asarray(f.positions, dtype=np.float32)
        changed = np.any(fr32.view(np.uint32) != data["samples"][k].astype(np.float32).view(np.uint32), axis=1)
        pairs.append(Slid(f"{outs[0].name}[{k}]", fr32.astype(np.float64), out, changed, True))
    return pairs, []


def _pairs(case, folder, ref, partial=False):
    """Every output with its frame (partial: a failed run's, however many there are)."""
    mesh = case.mesh
    if case.mode in ("pc2", "mdd"):
        return _cache_pairs(case, folder) if not partial else ([], [])
    if case.mode == "animation":
        return _animation_pairs(case, folder, ref)
    pairs, problems = [], []
    frames = _selected_frames(case)
    names = sorted(p.name for p in (folder / "out").iterdir()) if (folder / "out").exists() else []
    expect = sorted([f.name for f in frames] +
                    [f.name[:-5] + ".bin" for f in frames if f.format == "gltf"])
    if partial:
        frames = [f for f in frames if not f.bad]
    elif names != expect:
        problems.append(f"outputs {names[:6]} are not the selected frames {expect[:6]}")
    for f in frames:
        path = folder / "out" / f.name
        if not path.exists():
            continue
        src = folder / "frames" / f.name
        if f.format == "obj":
            pair, p = _obj_pair(f.name, src, path)
        else:
            pair, p = _glb_pair(f.name, src, path, mesh.raw_ids)
        problems += p
        if pair:
            pair.frame_spec = f
            pairs.append(pair)
    return pairs, problems


def _animation_pairs(case, folder, ref):
    mesh = case.mesh
    names = sorted(p.name for p in (folder / "out").iterdir())
    ref_names = sorted(p.name for p in pathlib.Path(ref).iterdir())
    if names != ref_names:
        return [], [f"outputs {names[:5]} differ from the unslid run's {ref_names[:5]}"]
    pairs, problems = [], []
    for n in names:
        a, b = pathlib.Path(ref) / n, folder / "out" / n
        if case.format == "obj":
            pair, p = _obj_pair(n, a, b)
        elif case.format == "glb":
            g = Glb.read(a)
            _, ids = weld(g.raw)
            pair, p = _glb_pair(n, a, b, ids)
            if len(ids) and ids.max() + 1 != len(mesh.positions):
                p.append(f"{n}: the posed frame welds to {ids.max() + 1} vertices, "
                         f"not the bind's {len(mesh.positions)}")
        else:
            ra, rb = read_pc2(a), read_pc2(b)
            p = []
            if ra["header"] != rb["header"]:
                p.append(f"{n}: header differs from the unslid cache's")
            for k in range(min(len(ra["samples"]), len(rb["samples"]))):
                fa, fb = ra["samples"][k], rb["samples"][k]
                changed = np.any(fa.view(np.uint32) != fb.view(np.uint32), axis=1)
                pr = Slid(f"{n}[{k}]", fa.astype(np.float64), fb.astype(np.float64), changed, True)
                pr.frame_spec = None
                pairs.append(pr)
            problems += p
            continue
        problems += p
        if pair:
            pair.frame_spec = None
            pairs.append(pair)
    return pairs, problems


def movers(case):
    """Vertex -> (component index) for every vertex that may move; its slide weight is
    case.w_eff[v]."""
    pins = set(case.pins or [])
    out = {}
    for ci, c in enumerate(case.comps):
        for v in c.interior:
            if v not in pins and case.w_eff[v] > 0:
                out[v] = ci
    return out


def check_slide(case, pair, may_move, patch_tris, identity=False, method=None):
    """The invariants of one slid frame (positions in welded ids)."""
    method = method or case.method
    problems = []
    label = pair.label
    if not np.all(np.isfinite(pair.out)):
        problems.append(f"{label}: a non-finite position")
        return problems
    changed = np.flatnonzero(pair.changed)
    wrong = [int(v) for v in changed if int(v) not in may_move]
    if wrong:
        roles = []
        pins = set(case.pins or [])
        for v in wrong[:5]:
            role = "outside every patch"
            for c in case.comps:
                if v in c.vertices:
                    role = "on a patch border" if v in c.boundary else (
                        "pinned" if v in pins else f"weight {case.w_eff[v]:g}")
            roles.append(f"{v} ({role})")
        problems.append(f"{label}: {len(wrong)} vertices that must keep the frame's bits "
                        f"changed: {', '.join(roles)}")
    diag = diagonal(pair.frame)
    scale = float(np.abs(pair.frame).max()) if len(pair.frame) else 0.0
    # 1e-9 of the diagonal, plus the rounding of the barycentric sum (a few ulps of the
    # coordinates: a frame collapsed to a point has no diagonal) and of float32 formats
    tol = ON_SURFACE * diag + 8 * 2.0 ** -52 * scale + \
        (4 * F32 * scale * math.sqrt(3) if pair.f32 else 0.0)
    by_comp = {}
    for v in changed:
        if int(v) in may_move:
            by_comp.setdefault(may_move[int(v)], []).append(int(v))
    for ci, verts in by_comp.items():
        tris = patch_tris[ci]
        corners = pair.frame[tris]
        verts = np.array(verts)
        w = case.w_eff[verts]
        p = pair.out[verts]
        chord = (method == "paper") & (w < 1)
        if np.any(chord):
            # paper: lerp(frame, slid, w): the slid point is frame + (out - frame) / w
            f0 = pair.frame[verts[chord]]
            p = p.copy()
            p[chord] = f0 + (p[chord] - f0) / w[chord][:, None]
        limit = np.full(len(verts), tol)
        limit[chord] = tol / w[chord] + 8 * 2.0 ** -52 * scale / w[chord]
        d = distances_to_triangles(p, corners, float(limit.max()) * 4)
        bad = np.flatnonzero(~(d <= limit))
        # the double formulas cancel on slivers: the few that fail are measured exactly
        bad = np.array([k for k in bad if not (np.isfinite(d[k]) and d[k] < 1e3 * limit[k] and
                                               exact_within(p[k], corners, limit[k]))], dtype=int)
        if len(bad):
            k = bad[np.argmax(d[bad] / np.maximum(limit[bad], 1e-300))]
            problems.append(
                f"{label}: {len(bad)} slid vertices off the frame's surface (patch {ci}); vertex "
                f"{int(verts[k])} at {d[k] / max(diag, 1e-300):.3g} of the diagonal "
                f"(allowed {limit[k] / max(diag, 1e-300):.3g}{', on the chord' if chord[k] else ''})")
    if identity:
        moved = np.linalg.norm(pair.out - pair.frame, axis=1).max() if len(pair.out) else 0
        if moved > tol:
            problems.append(f"{label}: the bind (or a rigid copy) as the frame moved by "
                            f"{moved / diag:.3g} of the diagonal (it comes back unchanged)")
    return problems


def _patch_triangles(case):
    out = []
    for c in case.comps:
        out.append(fan_triangles([case.mesh.faces[f] for f in c.faces]))
    return out


def _check_outputs(case, folder, ref):
    if case.no_slide:
        return _check_unchanged(case, folder)
    problems = []
    pairs, p = _pairs(case, folder, ref)
    problems += p
    may_move = movers(case)
    tris = _patch_triangles(case)
    for pair in pairs:
        spec = getattr(pair, "frame_spec", None)
        # the bind comes back unchanged; with elastic a rigid or uniformly scaled copy too
        identity = spec is not None and (
            (spec.note == "identity" and np.array_equal(pair.frame, case.mesh.positions) and
             (case.method == "elastic" or not case.mesh.degenerate)) or
            (spec.note == "rigid" and case.method == "elastic" and not pair.f32))
        problems += check_slide(case, pair, may_move, tris, identity)
    if case.report:
        problems += _check_report(case, folder, pairs)
    if case.dump:
        problems += _check_dumps(case, folder, pairs)
    if case.preview:
        problems += _check_previews(case, folder, pairs)
    return problems


def _check_unchanged(case, folder):
    """--no-slide: each output is its frame's bytes (a cache: the same cache)."""
    problems = []
    if case.mode == "files":
        for f in _selected_frames(case):
            out = folder / "out" / f.name
            if not out.exists():
                problems.append(f"--no-slide: no output for {f.name}")
            elif f.format == "obj" and out.read_bytes() != (folder / "frames" / f.name).read_bytes():
                problems.append(f"--no-slide: {f.name} is not its frame's bytes")
            elif f.format in ("glb", "gltf"):
                # the JSON is tinygltf's writing (lib/io/README.md); the buffer is the frame's
                a, b = Glb.read(folder / "frames" / f.name), Glb.read(out)
                if a.bin.rstrip(b"\0") != b.bin.rstrip(b"\0"):
                    problems.append(f"--no-slide: {f.name}'s buffer changed")
    elif not case.cache_obj:
        outs = sorted((folder / "out").iterdir())
        src = folder / "frames" / f"shot.{case.mode}"
        if not case.frames_spec:
            if len(outs) != 1 or outs[0].read_bytes() != src.read_bytes():
                problems.append(f"--no-slide: the cache {[p.name for p in outs]} is not the "
                                f"input's bytes")
        elif len(outs) != 1:
            problems.append(f"--no-slide: {len(outs)} caches written: {[p.name for p in outs]}")
        else:
            # --frames: the selected samples, each the input's bytes
            reader = read_pc2 if case.mode == "pc2" else read_mdd
            got, given = reader(outs[0])["samples"], reader(src)["samples"]
            chosen = [case.frames.index(f) for f in _selected_frames(case)]
            if len(got) != len(chosen) or got.tobytes() != given[chosen].tobytes():
                problems.append(f"--no-slide: {outs[0].name} is not the input's samples {chosen}")
    return problems


def _expected_patch_moves(case, ci):
    c = case.comps[ci]
    pins = set(case.pins or [])
    free = [v for v in c.interior if v not in pins]
    moving = [v for v in free if case.w_eff[v] > 0]
    return free, moving


def at_rest(case, ci, frame):
    """lib/pipeline/README.md, report: a patch with a free vertex whose every vertex is the
    bind's to float32 precision is at rest and comes back unchanged (`moved` 0)."""
    c = case.comps[ci]
    if not _expected_patch_moves(case, ci)[0]:
        return False
    verts = np.asarray(c.vertices, dtype=np.int64)
    return bool(np.array_equal(np.asarray(frame, dtype=np.float64)[verts].astype(np.float32),
                               case.mesh.positions[verts].astype(np.float32)))


def _finite_numbers(node, path="report"):
    if isinstance(node, dict):
        for k, v in node.items():
            yield from _finite_numbers(v, f"{path}.{k}")
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from _finite_numbers(v, f"{path}[{i}]")
    elif node is None:
        yield path
    elif isinstance(node, float) and not math.isfinite(node):
        yield path


def _no_constant(name):
    raise ValueError(f"JSON holds {name}")


def _check_report(case, folder, pairs):
    path = folder / "report.json"
    if not path.exists():
        return ["--report: no report written"]
    try:
        rep = json.loads(path.read_text(), parse_constant=_no_constant)
    except ValueError as e:
        return [f"report.json does not parse: {e}"]
    problems = []
    nulls = [p for p in _finite_numbers(rep) if not p.endswith((".weights", ".pins"))]
    if nulls:
        problems.append(f"report: null or non-finite values at {nulls[:4]}")
    if case.no_timings and "timings" in rep:
        problems.append("report: --report-no-timings but timings present")
    patches = rep.get("patches", [])
    if len(patches) != len(case.comps):
        problems.append(f"report: {len(patches)} patches, expected {len(case.comps)}")
        return problems
    for ci, (c, p) in enumerate(zip(case.comps, patches)):
        free, moving = _expected_patch_moves(case, ci)
        pins = set(case.pins or [])
        want = {"faces": len(c.faces), "vertices": len(c.vertices), "free": len(free),
                "pinned": len([v for v in c.interior if v in pins]), "loops": len(c.loops),
                "skipped": not free}
        if "moving" in p:
            want["moving"] = 0 if not free else len(moving)
        got = {k: p.get(k) for k in want}
        if got != want:
            problems.append(f"report: patch {ci} says {got}, expected {want}")
    controls = rep.get("controls", {})
    if case.pins is not None:
        pins = set(case.pins)
        inner = {v for c in case.comps for v in c.interior}
        want = {"pins_requested": len(pins), "pins_ignored": len(pins - inner)}
        got = {k: controls.get(k) for k in want}
        if got != want:
            problems.append(f"report: controls say {got}, expected {want}")
    frames = rep.get("frames", [])
    if case.mode == "files":
        want = [(f"frames/{f.name}", f"out/{f.name}") for f in _selected_frames(case)]
        got = [(fr.get("path"), fr.get("output")) for fr in frames]
        if got != want:
            problems.append(f"report: frames {got[:3]}, expected {want[:3]} (command-line order)")
    if len(frames) != len(pairs) and case.mode in ("files", "pc2", "mdd"):
        problems.append(f"report: {len(frames)} frames, {len(pairs)} outputs")
        return problems
    total_moved = 0
    total_max = 0.0
    for k, fr in enumerate(frames):
        fps = fr.get("patches", [])
        if len(fps) != len(case.comps):
            problems.append(f"report: frame {k} has {len(fps)} patches")
            continue
        pair = pairs[k] if k < len(pairs) else None
        frame_max = 0.0
        for ci, fp in enumerate(fps):
            free, moving = _expected_patch_moves(case, ci)
            total_moved += fp.get("moved", 0)
            frame_max = max(frame_max, fp.get("max_slide", 0))
            if case.method == "elastic":
                want_moved = len(moving) if free else 0
                if stop_problem(fp.get("stop")):
                    problems.append(f"report: frame {k} patch {ci} {stop_problem(fp.get('stop'))}")
                # lib/elastic/README.md rule 10: an escalated pass runs the rounds again
                fits, steps = _elastic_limits(case)
                passes = 1 + fp.get("escalations", 0)
                if fp.get("iterations", 0) > passes * fits * steps:
                    problems.append(f"report: frame {k} patch {ci} took {fp.get('iterations')} "
                                    f"steps; {passes} passes x --rotation-fits {fits} x "
                                    f"--max-iterations {steps}")
                # lib/elastic/README.md "Guarantees": the search turns no slid triangle against
                # the frame's (holds); the map counts the ones it turns (`flips`), which the
                # report carries, and promises no fold-freedom. Not kept where weights between 0
                # and 1 meet (U + w (u - U) is not line-searched): checked where every weight is
                # 0 or 1.
                fractional = any(0 < case.w_eff[v] < 1 for v in moving)
                if fp.get("flips") and not fractional and searches(case):
                    problems.append(f"report: frame {k} patch {ci}: {fp.get('flips')} flips "
                                    f"(elastic slides fold-free)")
                eb, ea = fp.get("energy_before"), fp.get("energy_after")
                if isinstance(eb, (int, float)) and isinstance(ea, (int, float)) and \
                        ea > eb * (1 + 1e-12) + 1e-300:
                    problems.append(f"report: frame {k} patch {ci} energy rose {eb} -> {ea}")
            else:
                want_moved = len([v for v in free if case.w_eff[v] > 0]) if free else 0
            if pair is not None and "at_rest" in fp and \
                    bool(fp["at_rest"]) != at_rest(case, ci, pair.frame):
                problems.append(f"report: frame {k} patch {ci} at_rest {fp['at_rest']!r}, the "
                                f"frame says {at_rest(case, ci, pair.frame)}")
            if fp.get("at_rest"):
                want_moved = 0
                # The figures describe what was written: the frame itself.
                if fp.get("flips", 0) != 0 or fp.get("energy_after") != fp.get("energy_before"):
                    problems.append(f"report: frame {k} patch {ci} at rest, yet flips "
                                    f"{fp.get('flips')} and energy {fp.get('energy_before')} -> "
                                    f"{fp.get('energy_after')}")
            if fp.get("moved") != want_moved:
                problems.append(f"report: frame {k} patch {ci} moved {fp.get('moved')}, expected "
                                f"{want_moved} (free {len(free)}, weight > 0: {len(moving)})")
            if pair is not None:
                verts = moving if free else []
                if verts:
                    d = np.linalg.norm(pair.out[verts] - pair.frame[verts], axis=1)
                    m = float(d.max())
                    ms = fp.get("max_slide", 0)
                    tol = 1e-12 * max(m, 1e-300) + (8 * F32 * float(np.abs(pair.frame).max())
                                                    if pair.f32 else 1e-300)
                    if abs(ms - m) > tol and not (pair.f32 and ms >= 0):
                        problems.append(f"report: frame {k} patch {ci} max_slide {ms!r}, the "
                                        f"outputs say {m!r}")
        total_max = max(total_max, frame_max)
    totals = rep.get("totals", {})
    if totals.get("moved") != total_moved:
        problems.append(f"report: totals.moved {totals.get('moved')} != sum {total_moved}")
    if totals.get("frames") != len(frames):
        problems.append(f"report: totals.frames {totals.get('frames')} != {len(frames)}")
    if totals.get("max_slide") != total_max:
        problems.append(f"report: totals.max_slide {totals.get('max_slide')} != max {total_max}")
    return problems


def searches(case):
    """The elastic case runs the search (`--solver search`), not the map."""
    return "--solver" in case.options and \
        case.options[case.options.index("--solver") + 1] == "search"


def _elastic_limits(case):
    fits, steps = 3, 100
    if "--rotation-fits" in case.options:
        fits = int(case.options[case.options.index("--rotation-fits") + 1])
    if "--max-iterations" in case.options:
        steps = int(case.options[case.options.index("--max-iterations") + 1])
    return fits, steps


def _stems(case, pairs):
    if case.mode == "files":
        return [os.path.splitext(p.label)[0] for p in pairs]
    return None


def _written(case, folder, pairs, option, names):
    """The files `option` (--dump, --preview) wrote into its folder, and a problem when they are
    not `names(stems, live)`: the frames' file stems and the patches with a free vertex (file
    frames only: a cache's or an animation's frames are named otherwise)."""
    d = folder / option.lstrip("-")
    files = sorted(p.name for p in d.iterdir()) if d.exists() else []
    live = [ci for ci in range(len(case.comps)) if _expected_patch_moves(case, ci)[0]]
    stems = _stems(case, pairs)
    problems = []
    if stems is not None:
        want = sorted(names(stems, live))
        if files != want:
            problems.append(f"{option} wrote {files[:6]}, expected {want[:6]}")
    return d, files, problems


def _check_dumps(case, folder, pairs):
    d, files, problems = _written(
        case, folder, pairs, "--dump",
        lambda stems, live: (f"{s}.patch{ci:03d}.{k}.exr" for s in ["bind"] + stems
                             for ci in live for k in ("id", "geom")))
    size = _lookup_size(case)
    for name in files:
        try:
            img = read_exr(d / name)
        except FormatError as e:
            problems.append(str(e))
            continue
        if (img["width"], img["height"]) != (size, size):
            problems.append(f"{name}: {img['width']}x{img['height']}, --lookup-size {size}")
        for ch, plane in img["channels"].items():
            if plane.dtype.kind == "f" and not np.all(np.isfinite(plane)):
                problems.append(f"{name}: channel {ch} holds NaN or infinity")
    return problems


def _lookup_size(case):
    if "--lookup-size" in case.options:
        return int(case.options[case.options.index("--lookup-size") + 1])
    return 1024


def _check_previews(case, folder, pairs):
    d, files, problems = _written(
        case, folder, pairs, "--preview",
        lambda stems, live: (f"{s}.patch{ci:03d}.png" for s in stems for ci in live))
    for name in files:
        try:
            img = read_png(d / name)
        except FormatError as e:
            problems.append(str(e))
            continue
        if (img["width"], img["height"]) != (case.preview_size, case.preview_size):
            problems.append(f"{name}: {img['width']}x{img['height']}, --preview-size "
                            f"{case.preview_size}")
    return problems


def reference_args(case):
    """The unslid frames of an --animation case: the same clip, sampling and format, nothing
    sliding (--strength 0, a one-face patch)."""
    args = ["-q", "--patch", "ref_patch.txt", "--strength", "0", "--animation", str(case.clip),
            "--format", case.format, "-o", "ref"]
    if case.fps:
        args += ["--fps", str(case.fps)]
    if case.frames_spec:
        args += ["--frames", case.frames_spec]
    return args + ["bind.glb"]


def describe(case):
    lines = [f"seed {case.seed}: " + "; ".join(case.notes)]
    lines.append(f"method {case.method}, mode {case.mode}, options {case.options}"
                 f"{' --require-converged' if getattr(case, 'require_converged', False) else ''}"
                 f"{' --window %d' % case.window if getattr(case, 'window', 0) else ''}"
                 f"{' --window-ends cycle' if getattr(case, 'window_cycle', False) else ''}, pins "
                 f"{None if case.pins is None else len(case.pins)}, weights "
                 f"{'file' if case.weight_file else case.colour_channel}, strength {case.strength}")
    if case.frames_spec:
        lines.append(f"--frames {case.frames_spec}")
    if case.mode != "animation":
        lines.append("frames: " + ", ".join(f"{f.number}:{f.note}{' (' + f.bad + ')' if f.bad else ''}"
                                            for f in case.frames))
    lines.append(f"expected: {expected_codes(case)[1]}")
    return "\n  ".join(lines)
