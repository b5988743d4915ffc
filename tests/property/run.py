#!/usr/bin/python3
"""Random whole-pipeline test of skinslide (tests/property/README.md): seeded random patch
selections x options x frames over every mesh in data/ and ../shared/data and small degenerate
ones, through the command line and the Python module, each case checked against the README's
promises. Every failure prints its seed and a command that reproduces it.

  tests/property/run.py --skinslide build/skinslide --python build/python --seconds 75
  tests/property/run.py --skinslide build/skinslide --minutes 30 --seed 7     # on demand
  tests/property/run.py --skinslide build/skinslide --case 28000017           # one case again
"""
import argparse
import os
import pathlib
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time
import traceback

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import cli_case  # noqa: E402
import py_case  # noqa: E402
from cases import catalogue  # noqa: E402

ROOT = HERE.parents[1]


class Context:
    """What every case shares: the binary and the options its --help lists, a cache of posed
    glTF frames, the build kind, the running case's time limit."""

    def __init__(self, args, work):
        self.binary = os.path.abspath(args.skinslide)
        self.python_dir = os.path.abspath(args.python) if args.python else None
        self.sanitized = args.sanitized
        self.work = pathlib.Path(work)
        self.case_limit = args.case_timeout
        self._case_end = None
        self._posed = {}
        shown = subprocess.run([self.binary, "--help"], capture_output=True, text=True,
                               timeout=60)
        self.options = set(re.findall(r"--[a-z][a-z0-9-]*", shown.stdout))

    def start_case(self):
        self._case_end = time.monotonic() + self.case_limit

    @property
    def timeout(self):
        """Seconds left for the running case's next run: the limit is the whole case's (every
        run of it), so the test ends within its budget plus one case's limit."""
        if self._case_end is None:
            return self.case_limit
        return max(1.0, self._case_end - time.monotonic())

    def posed(self, mesh, rng):
        """A frame of the character's first clip, posed by skinslide unslid (--strength 0)."""
        if mesh.name not in self._posed:
            out = self.work / "posed" / mesh.name
            out.mkdir(parents=True, exist_ok=True)
            (out.parent / "one_face.txt").write_text("0\n")
            done = subprocess.run([self.binary, "-q", "--patch", str(out.parent / "one_face.txt"),
                                   "--strength", "0", "--animation", "0", "--format", "glb",
                                   "-o", str(out), mesh.path], capture_output=True, text=True,
                                  timeout=self.timeout)
            files = sorted(str(p) for p in out.glob("*.glb")) if done.returncode == 0 else []
            if done.returncode != 0:
                print(f"note: posing {mesh.name} failed (exit {done.returncode}): "
                      f"{done.stderr.strip()[-300:]}", flush=True)
            self._posed[mesh.name] = files
        files = self._posed[mesh.name]
        return rng.choice(files) if files else None


def keep_case(folder, keep_dir, seed, kind):
    """Copies the case's folder (symlinks resolved: shared meshes copied in) to keep_dir."""
    dest = pathlib.Path(keep_dir) / f"{kind}-{seed}"
    if dest.exists():
        shutil.rmtree(dest)
    shutil.copytree(folder, dest, symlinks=False,
                    ignore=shutil.ignore_patterns("out", "dump", "preview", "ref", "report.json",
                                                  "result*"))
    return dest


def shell_quote(args):
    import shlex
    return " ".join(shlex.quote(a) for a in args)


def run_cli_case(seed, meshes, ctx, folder):
    case = cli_case.build(seed, meshes, ctx)
    args = cli_case.write(case, folder)
    ref = None
    pre = []
    if case.mode == "animation":
        (folder / "ref_patch.txt").write_text("0\n")
        ref_args = cli_case.reference_args(case)
        r0 = cli_case.run(ctx.binary, ref_args, folder, ctx.timeout)
        pre = cli_case.process_failures(r0, "the unslid reference run")
        if r0.code == 2:
            case.usage_error = "--frames selects no sample of the clip (as the unslid run says)"
        elif r0.code != 0 and not pre:
            pre.append(f"the unslid reference run exited {r0.code}: {r0.stderr.strip()[-300:]}")
        ref = folder / "ref"
    for f in case.frames:
        if f.format in ("glb", "gltf") and f.source is None:
            from meshio import Glb, weld
            g = Glb.read(folder / "frames" / f.name)
            welded, ids = weld(g.raw)
            if len(welded) != len(case.mesh.positions) or not (ids == case.mesh.raw_ids).all():
                f.weld_changed = True
    r = cli_case.run(ctx.binary, args, folder, ctx.timeout)
    failures = pre + cli_case.check(case, folder, r, ref if case.mode == "animation" else None)
    rng = random.Random(seed ^ 0xA6A1)
    if not failures and r.code == 0 and case.mode == "files" and rng.random() < 0.25:
        again, names = cli_case.rerun_args(case, args, rng)
        r2 = cli_case.run(ctx.binary, again, folder, ctx.timeout)
        failures += cli_case.process_failures(r2, "the re-run")
        if r2.code != 0:
            failures.append(f"the re-run ({cli_case.shell_words(again)}) exited {r2.code}")
        else:
            for n in names:
                if (folder / "out2" / n).read_bytes() != (folder / "out" / n).read_bytes():
                    failures.append(f"{n}: other bytes with -j and frames changed "
                                    f"({cli_case.shell_words(again)})")
    if not failures and r.code == 0 and case.mode in ("pc2", "mdd") and not case.frames_spec \
            and not case.cache_obj and len(case.frames) >= 2 and rng.random() < 0.4:
        failures += farm_chunks(case, args, folder, ctx, rng)
    return case, args, r, failures


def farm_chunks(case, args, folder, ctx, rng):
    """README "Farm": the shot cut into two --frames chunks and joined is byte for byte the
    whole run's cache."""
    numbers = [f.number for f in case.frames]
    cut = rng.randrange(1, len(numbers))
    problems = []
    base = [a for a in args if a not in ("out",)]
    base = [a for k, a in enumerate(base) if not (a == "-o")]
    for first, last in ((numbers[0], numbers[cut - 1]), (numbers[cut], numbers[-1])):
        chunk = base[:-1] + ["-o", "chunks", "--frames", f"{first}-{last}", base[-1]]
        r = cli_case.run(ctx.binary, chunk, folder, ctx.timeout)
        problems += cli_case.process_failures(r, "a farm chunk")
        if r.code != 0:
            return problems + [f"the chunk {first}-{last} exited {r.code}: {r.stderr.strip()[-300:]}"]
    chunks = sorted(str(p.relative_to(folder)) for p in (folder / "chunks").iterdir())
    r = cli_case.run(ctx.binary, ["join", "-q", "-o", "joined"] + chunks, folder, ctx.timeout)
    problems += cli_case.process_failures(r, "skinslide join")
    if r.code != 0:
        return problems + [f"skinslide join {' '.join(chunks)} exited {r.code}: {r.stderr.strip()[-300:]}"]
    whole = sorted((folder / "out").iterdir())
    joined = sorted((folder / "joined").iterdir())
    if [p.name for p in joined] != [p.name for p in whole]:
        return problems + [f"join wrote {[p.name for p in joined]}, the whole run {[p.name for p in whole]}"]
    if joined[0].read_bytes() != whole[0].read_bytes():
        problems.append(f"the chunks {chunks} joined differ from the whole run's {whole[0].name}")
    return problems


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--skinslide", default=os.environ.get("SKINSLIDE", str(ROOT / "build/skinslide")))
    p.add_argument("--python", default=os.environ.get("SKINSLIDE_PYTHON_DIR"),
                   help="folder holding the skinslide Python module (build/python); "
                        "without it the module's cases are left out")
    p.add_argument("--shared", default=os.environ.get("SKINSLIDE_SHARED_DIR", str(ROOT.parent / "shared")))
    p.add_argument("--seed", type=int, default=28, help="base seed (CI: 28)")
    p.add_argument("--seconds", type=float, default=None, help="time budget (default 75)")
    p.add_argument("--minutes", type=float, default=None, help="time budget in minutes")
    p.add_argument("--cases", type=int, default=None, help="stop after this many cases")
    p.add_argument("--case", type=int, action="append", default=[],
                   help="run only this case seed (repeatable): reproduces a printed failure")
    p.add_argument("--python-share", type=float, default=0.3,
                   help="share of cases run through the Python module")
    p.add_argument("--case-timeout", type=float, default=None,
                   help="seconds a case may take, all its runs together (default 180; "
                        "sanitized 600)")
    p.add_argument("--sanitized", action="store_true",
                   default=os.environ.get("SKINSLIDE_PROPERTY_SANITIZED", "") not in ("", "0"),
                   help="a sanitizer build: smaller cases, longer time limits")
    p.add_argument("--keep", default=None, help="folder for failing cases' inputs "
                   "(default: property-failures beside the work folder)")
    p.add_argument("--work", default=None, help="scratch folder (default: a temporary one)")
    p.add_argument("--stop-after", type=int, default=10, help="stop after this many failures")
    args = p.parse_args()
    if args.case_timeout is None:
        args.case_timeout = 600.0 if args.sanitized else 180.0
    budget = args.seconds if args.seconds is not None else (
        args.minutes * 60 if args.minutes is not None else 75.0)
    if not os.access(args.skinslide, os.X_OK):
        print(f"FAIL: no skinslide binary at {args.skinslide}")
        return 1
    require = os.environ.get("SKINSLIDE_REQUIRE_SHARED") == "1"
    shared = pathlib.Path(args.shared)
    if not (shared / "data").exists():
        if require:
            print(f"FAIL: missing {shared}/data (SKINSLIDE_REQUIRE_SHARED=1)")
            return 1
        print(f"note: no {shared}/data: data/ and the synthetic meshes only")
    python_dir = args.python
    if python_dir and not list(pathlib.Path(python_dir).glob("skinslide*.so")):
        print(f"note: no Python module in {python_dir}: command-line cases only")
        python_dir = None
    args.python = python_dir

    work = pathlib.Path(args.work or tempfile.mkdtemp(prefix="skinslide-property-"))
    work.mkdir(parents=True, exist_ok=True)
    keep = pathlib.Path(args.keep or (work.parent / "skinslide-property-failures"))
    ctx = Context(args, work)
    meshes = catalogue(ROOT, shared, work)
    print(f"skinslide property test: base seed {args.seed}, budget {budget:.0f} s, "
          f"{len(meshes)} meshes, {'sanitized build, ' if args.sanitized else ''}"
          f"{'CLI and Python' if python_dir else 'CLI only'}; work {work}", flush=True)

    seeds = args.case or None
    t0 = time.monotonic()
    counts = {"cli": 0, "python": 0}
    codes = {}
    failed = []
    slowest = (0.0, None)
    i = 0
    while True:
        if seeds is not None:
            if i >= len(seeds):
                break
            seed = seeds[i]
        else:
            if args.cases is not None and i >= args.cases:
                break
            if time.monotonic() - t0 > budget:
                break
            seed = args.seed * 1_000_000 + i
        i += 1
        kind = "python" if python_dir and random.Random(seed * 7 + 3).random() < args.python_share else "cli"
        folder = work / f"{kind}-{seed}"
        shutil.rmtree(folder, ignore_errors=True)
        folder.mkdir(parents=True)
        ctx.start_case()
        started = time.monotonic()
        try:
            if kind == "cli":
                case, argv, r, failures = run_cli_case(seed, meshes, ctx, folder)
                code = r.code
            else:
                case, argv, code, failures = py_case.run_case(seed, meshes, ctx, folder)
        except Exception:
            case, code = None, "driver error"
            failures = ["the test driver failed:\n" + traceback.format_exc()]
        counts[kind] += 1
        if time.monotonic() - started > slowest[0]:
            slowest = (time.monotonic() - started, seed)
        codes[code] = codes.get(code, 0) + 1
        if failures:
            dest = keep_case(folder, keep, seed, kind)
            desc = (cli_case.describe(case) if kind == "cli" else py_case.describe(case)) if case else ""
            (dest / "failure.txt").write_text(desc + "\n\n" + "\n".join(failures) + "\n")
            if kind == "cli":
                (dest / "repro.sh").write_text(
                    "#!/bin/sh\n# " + desc.replace("\n", "\n# ") + "\ncd \"$(dirname \"$0\")\" && "
                    + shell_quote(["${SKINSLIDE:-" + ctx.binary + "}"]).replace("'", "\"")
                    + " " + shell_quote(argv) + "\n")
            else:
                (dest / "repro.sh").write_text(
                    "#!/bin/sh\n# " + desc.replace("\n", "\n# ") + "\ncd \"$(dirname \"$0\")\" && "
                    f"PYTHONPATH={python_dir} /usr/bin/python3 {HERE / 'py_worker.py'} spec.json\n")
            os.chmod(dest / "repro.sh", 0o755)
            failed.append(seed)
            print(f"\nFAIL {kind} case {seed}\n  {desc}\n  " + "\n  ".join(failures) +
                  f"\n  reproduce: sh {dest}/repro.sh\n  or: {sys.argv[0]} --skinslide "
                  f"{ctx.binary}{' --python ' + python_dir if python_dir else ''} --case {seed}",
                  flush=True)
            if len(failed) >= args.stop_after:
                print(f"stopping after {len(failed)} failures")
                break
        else:
            shutil.rmtree(folder, ignore_errors=True)
    elapsed = time.monotonic() - t0
    print(f"\n{counts['cli']} command-line and {counts['python']} Python cases in {elapsed:.0f} s; "
          f"outcomes {dict(sorted(codes.items(), key=str))}; slowest case {slowest[0]:.1f} s "
          f"(seed {slowest[1]}); {len(failed)} failed"
          + (f": seeds {failed}" if failed else ""), flush=True)
    if not args.work:  # failing cases are in keep
        shutil.rmtree(work, ignore_errors=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
