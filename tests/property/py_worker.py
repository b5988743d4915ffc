#!/usr/bin/python3
"""Runs one Python-module case in its own interpreter, so that a crash kills this process and
not the test: py_worker.py spec.json. Reads the case's arrays from spec.npz beside it, writes
result.json (the slider's patches, each frame's report, or the error's kind and message) and
result.npz (each frame's slid positions)."""
import concurrent.futures
import json
import pathlib
import sys

import numpy as np

import skinslide


def main():
    spec_path = pathlib.Path(sys.argv[1]).resolve()
    spec = json.loads(spec_path.read_text())
    arrays = np.load(spec_path.with_suffix(".npz"))
    folder = spec_path.parent
    result = {"stage": "set-up"}
    out = {}

    def as_given(key, form):
        a = arrays[key]
        if form == "list":
            return a.tolist()
        if form == "int32":
            return a.astype(np.int32)
        return a

    mangle = spec.get("mangle")
    try:
        bind = arrays["bind"]
        if mangle == "nan_bind":
            bind = bind.copy()
            bind[len(bind) // 2, 1] = np.nan
        if spec["faces"] == "flat":
            faces, kw = arrays["face_vertices"], {"face_sizes": arrays["face_sizes"]}
            if spec["faces_form"] == "int32":
                faces = faces.astype(np.int32)
        elif spec["faces"] == "table":
            faces, kw = arrays["face_table"], {}
        else:
            sizes = arrays["face_sizes"]
            flat = arrays["face_vertices"].tolist()
            faces, at = [], 0
            for s in sizes:
                faces.append(flat[at:at + s])
                at += s
            kw = {}
        if mangle in ("degenerate_face_unselected", "degenerate_face_selected", "two_corner_face"):
            # one more face after the others (their ids unchanged), as a list of polygons
            if spec["faces"] == "lists":
                polygons = faces
            else:
                flat, sizes = arrays["face_vertices"].tolist(), arrays["face_sizes"].tolist()
                polygons, at = [], 0
                for n in sizes:
                    polygons.append(flat[at:at + n])
                    at += n
            polygons = polygons + ([[0, 0, 1]] if mangle != "two_corner_face" else [[0, 1]])
            faces, kw = polygons, {}
        patches = [as_given(f"patch{i}", spec["patch_form"]) for i in range(spec["patch_count"])]
        if mangle == "degenerate_face_selected":
            patches[0] = list(patches[0]) + [len(faces) - 1]
        if spec["single_patch"]:
            patches = patches[0]
        if spec["pins"]:
            kw["pins"] = as_given("pins", spec["patch_form"])
        if spec["weights"]:
            kw["weights"] = arrays["weights"]
        if mangle == "weight_above_one":
            kw["weights"] = np.full(len(bind), 1.5)
        if spec["strength"] is not None:
            kw["strength"] = spec["strength"]
        if mangle in ("negative_strength", "nan_strength"):
            kw["strength"] = -1.0 if mangle == "negative_strength" else float("nan")
        if spec["outer"]:
            kw["outer_loop_vertices"] = spec["outer"]
        if spec["corners"]:
            kw["corners"] = spec["corners"]
        slider = skinslide.Slider(bind, faces, patches, method=spec["method"],
                                  threads=spec["threads"], **kw, **spec["options"])
        result["patches"] = slider.patches
        result["options"] = slider.options
        result["stage"] = "slide"
        frames = [arrays[f"frame{k}"] for k in range(spec["frame_count"])]
        if spec["frame_form"] == "float32":
            frames = [f.astype(np.float32) for f in frames]
        elif spec["frame_form"] == "fortran":
            frames = [np.asfortranarray(f) for f in frames]
        elif spec["frame_form"] == "strided":
            frames = [np.repeat(f, 2, axis=1)[:, ::2] for f in frames]  # a view, not contiguous
        if mangle == "nan_frame" and frames:
            frames[0] = frames[0].copy()
            frames[0][0, 2] = np.nan
        if mangle == "short_frame" and frames:
            frames[0] = frames[0][:-1]
        window = spec["window"]
        reports = []
        if window:  # one sequence, each frame with its neighbours' slides
            slid, reports = slider.slide_sequence(frames, window=window,
                                                  window_ends=spec["window_ends"],
                                                  edge_spread=spec["edge_spread"])
            for k in range(len(frames)):
                out[f"out{k}"] = slid[k]
        else:
            for k, f in enumerate(frames):
                slid, report = slider.slide(f, edge_spread=spec["edge_spread"])
                out[f"out{k}"] = slid
                reports.append(report)
        result["reports"] = reports
        if spec["pool"] and frames:
            if window:
                again = list(slider.slide_sequence(frames, window=window,
                                                   window_ends=spec["window_ends"], threads=3)[0])
            else:
                with concurrent.futures.ThreadPoolExecutor(max_workers=3) as pool:
                    again = list(pool.map(lambda f: slider.slide(f)[0], frames))
            result["pool_same"] = all(a.tobytes() == out[f"out{k}"].tobytes()
                                      for k, a in enumerate(again))
        result["stage"] = "done"
    except skinslide.Error as e:
        result["error"] = {"kind": e.kind, "type": type(e).__name__, "message": str(e)}
    except Exception as e:  # noqa: BLE001: any other exception is reported, not a crash
        result["error"] = {"kind": None, "type": type(e).__name__, "message": str(e)}
    np.savez(folder / "result.npz", **out)
    (folder / "result.json").write_text(json.dumps(result, default=_plain))


def _plain(x):
    if isinstance(x, (np.integer,)):
        return int(x)
    if isinstance(x, (np.floating,)):
        return float(x)
    if isinstance(x, np.ndarray):
        return x.tolist()
    return str(x)


if __name__ == "__main__":
    main()
