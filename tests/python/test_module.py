"""The Python module against the command line: the same bits on data/ and on a shared character,
both methods; parallel frames; errors with their kinds; the file readers."""
import concurrent.futures
import json
import pathlib

import numpy as np
import pytest

import skinslide
from conftest import ROOT, obj_positions, shared

DATA = ROOT / "data"
METHODS = ["elastic", "paper"]


def slider_from_files(bind_path, patch_path, **options):
    positions, face_vertices, face_sizes = skinslide.read_mesh(str(bind_path))
    patch = skinslide.read_patch(str(patch_path), len(face_sizes))
    return skinslide.Slider(positions, face_vertices, patch, face_sizes=face_sizes, **options)


def frame_positions(path):
    return skinslide.read_mesh(str(path))[0]


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("case", ["elbow", "face"])
def test_data_slides_to_the_commands_bits(case, method, cli, tmp_path):
    bind, patch = DATA / case / "bind.obj", DATA / case / "patch.txt"
    frames = sorted((DATA / case / "frames").glob("*.obj"))
    cli("--method", method, "--patch", patch, bind, *frames, "-o", tmp_path)
    slider = slider_from_files(bind, patch, method=method)
    moved = 0
    for frame in frames:
        positions, report = slider.slide(frame_positions(frame))
        expected = obj_positions(tmp_path / frame.name)
        assert positions.dtype == np.float64 and positions.shape == expected.shape
        assert positions.tobytes() == expected.tobytes(), frame.name
        moved += report["moved"]
    assert moved > 0, "the deformed frames slide"


@pytest.mark.parametrize("method", METHODS)
def test_a_shared_character_slides_to_the_commands_bits(method, cli, tmp_path):
    glb = shared("data/gltf/CesiumMan.glb")
    # The character's walk posed by the command itself, unslid (--strength 0): OBJ frames.
    posed = tmp_path / "posed"
    positions, face_vertices, face_sizes = skinslide.read_mesh(str(glb))
    # The knees: faces whose centre lies between 20% and 40% up the figure (z up).
    corners = positions[face_vertices.reshape(-1, 3)]
    z = corners[:, :, 2].mean(axis=1)
    low, high = positions[:, 2].min(), positions[:, 2].max()
    faces = np.flatnonzero((z >= low + 0.2 * (high - low)) & (z <= low + 0.4 * (high - low)))
    patch = tmp_path / "knees.txt"
    patch.write_text(" ".join(map(str, faces)) + "\n")
    cli("--patch", patch, "--animation", "0", "--frames", "0-47:12", "--format", "obj",
        "--strength", "0", "-o", posed, glb)
    frames = sorted(posed.glob("*.obj"))
    assert len(frames) == 4
    slid = tmp_path / "slid"
    cli("--method", method, "--patch", patch, glb, *frames, "-o", slid)
    # glTF faces are triangles: the (faces, 3) layout serves as well as face_sizes.
    slider = skinslide.Slider(positions, face_vertices.reshape(-1, 3), faces, method=method)
    assert sum(p["free"] for p in slider.patches) > 0
    moved = 0
    for frame in frames:
        out, report = slider.slide(frame_positions(frame))
        assert out.tobytes() == obj_positions(slid / frame.name).tobytes(), frame.name
        moved += report["moved"]
    assert moved > 0, "the walking knees slide"


def test_a_thread_pool_gives_the_bits_of_a_serial_run():
    slider = slider_from_files(DATA / "face" / "bind.obj", DATA / "face" / "patch.txt")
    frames = [frame_positions(f) for f in sorted((DATA / "face" / "frames").glob("*.obj"))]
    serial = [slider.slide(f)[0].tobytes() for f in frames]
    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        parallel = [r[0].tobytes() for r in pool.map(slider.slide, frames)]
    assert parallel == serial


@pytest.mark.parametrize("window,ends", [(1, "one-sided"), (3, "one-sided"), (2, "cycle")])
def test_a_windowed_sequence_slides_to_the_commands_bits(window, ends, cli, tmp_path):
    bind, patch = DATA / "elbow" / "bind.obj", DATA / "elbow" / "patch.txt"
    frames = sorted((DATA / "elbow" / "frames").glob("*.obj"))
    cli("--window", str(window), "--window-ends", ends, "--patch", patch, bind, *frames,
        "-o", tmp_path)
    slider = slider_from_files(bind, patch)
    poses = [frame_positions(f) for f in frames]
    serial, reports = slider.slide_sequence(poses, window=window, window_ends=ends)
    assert serial.shape == (len(frames), slider.vertex_count, 3)
    for k, frame in enumerate(frames):
        assert serial[k].tobytes() == obj_positions(tmp_path / frame.name).tobytes(), frame.name
    assert all("window_returned" in p for r in reports for p in r["patches"])
    alone = [slider.slide(f)[0].tobytes() for f in poses]
    assert [s.tobytes() for s in serial] != alone, "the window changes the slide"
    threaded, _ = slider.slide_sequence(np.stack(poses), window=window, window_ends=ends,
                                        threads=4)
    assert threaded.tobytes() == serial.tobytes(), "any thread count, one (F, V, 3) array too"


def test_a_sequence_without_a_window_is_each_frames_slide():
    slider = slider_from_files(DATA / "face" / "bind.obj", DATA / "face" / "patch.txt",
                               method="paper")
    poses = [frame_positions(f) for f in sorted((DATA / "face" / "frames").glob("*.obj"))]
    slid, reports = slider.slide_sequence(poses, threads=3)
    for k, pose in enumerate(poses):
        out, report = slider.slide(pose)
        assert slid[k].tobytes() == out.tobytes()
        assert reports[k]["moved"] == report["moved"]
    assert slider.slide_sequence([])[0].shape == (0, slider.vertex_count, 3)


def test_a_sequence_is_refused_with_its_fault_named():
    elastic = slider_from_files(DATA / "elbow" / "bind.obj", DATA / "elbow" / "patch.txt")
    paper = slider_from_files(DATA / "elbow" / "bind.obj", DATA / "elbow" / "patch.txt",
                              method="paper")
    pose = frame_positions(DATA / "elbow" / "frames" / "elbow.0005.obj")
    window, ends = skinslide.sequence_option_specs()
    with pytest.raises(skinslide.UsageError, match=r"window 101 is out of its range \[0, 100\]"):
        elastic.slide_sequence([pose], window=window["max"] + 1)
    assert window | {"help": ""} == {
        "name": "window", "option": "--window", "method": "elastic", "type": "int", "default": 0,
        "min": 0, "max": 100, "help": "", "research": False, "needs": None}
    assert (ends["name"], ends["default"], ends["choices"]) == \
        ("window_ends", "one-sided", ["one-sided", "cycle"])
    with pytest.raises(skinslide.UsageError, match="unknown window end 'loop' .one-sided, cycle."):
        elastic.slide_sequence([pose], window=1, window_ends="loop")
    with pytest.raises(skinslide.UsageError, match="cycle ends .* give a window too"):
        elastic.slide_sequence([pose], window_ends="cycle")
    with pytest.raises(skinslide.UsageError, match="window -1"):
        elastic.slide_sequence([pose], window=-1)
    with pytest.raises(skinslide.UsageError, match="elastic method's; .* paper method"):
        paper.slide_sequence([pose], window=2)
    with pytest.raises(skinslide.InputError, match="frame 1 has 9 coordinates"):
        elastic.slide_sequence([pose, pose[:3]], window=2)
    broken = pose.copy()
    broken[7, 1] = np.nan
    with pytest.raises(skinslide.InputError, match="frame 2: vertex 7 is not finite"):
        elastic.slide_sequence([pose, pose, broken], window=1)
    with pytest.raises(skinslide.UsageError, match="each frame must be an array"):
        elastic.slide_sequence([pose, pose.ravel()], window=1)
    # A frame that cannot be relaxed fails every frame whose window holds it: the first of them,
    # frame 1, is raised, naming the neighbour, whatever the threads.
    huge = pose * 1e200
    with pytest.raises(skinslide.InputError,
                       match="^frame 1: its --window neighbour frame 2: patch 0: .* too large"):
        elastic.slide_sequence([pose, pose, huge, pose], window=1, threads=3)
    with pytest.raises(skinslide.InputError, match="^frame 2: patch 0: .* too large"):
        elastic.slide_sequence([pose, pose, huge, pose], threads=3)


def test_controls_from_files_match_the_command(cli, tmp_path):
    bind, patch = DATA / "face" / "bind.obj", DATA / "face" / "patch.txt"
    frame = DATA / "face" / "frames" / "face.0003.obj"
    positions = frame_positions(bind)
    weights, pins = tmp_path / "w.txt", tmp_path / "pins.txt"
    weights.write_text("".join(f"{v} {(v % 5) / 4}\n" for v in range(len(positions))))
    pins.write_text("10-20 55\n")
    cli("--method", "paper", "--patch", patch, "--weights", weights, "--pin", pins,
        "--strength", "0.8", bind, frame, "-o", tmp_path / "out")
    slider = slider_from_files(bind, patch, method="paper", strength=0.8,
                               weights=skinslide.read_weights(str(weights), len(positions)),
                               pins=skinslide.read_pins(str(pins), len(positions)))
    out, _ = slider.slide(frame_positions(frame))
    assert out.tobytes() == obj_positions(tmp_path / "out" / frame.name).tobytes()


def test_reports_carry_each_methods_figures():
    bind, patch = DATA / "elbow" / "bind.obj", DATA / "elbow" / "patch.txt"
    frame = frame_positions(DATA / "elbow" / "frames" / "elbow.0005.obj")
    elastic = slider_from_files(bind, patch)
    _, report = elastic.slide(frame, edge_spread=True)
    figures = report["patches"][0]
    assert figures["stop"] in ("converged", "passes", "small gain", "limit", "no step", "at rest",
                               "no descent")
    # converged only where the first-order measure says so (lib/elastic/README.md rule 10)
    assert figures["converged"] == (figures["first_order_share"] <= elastic.options["convergence"])
    assert figures["energy_after"] <= figures["energy_before"]
    assert figures["spread_slid"] < figures["spread_frame"], "sliding evens the stretch"
    assert elastic.options["method"] == "elastic" and elastic.method == "elastic"
    paper = slider_from_files(bind, patch, method="paper", density="uniform")
    _, report = paper.slide(frame)
    assert "cg_iterations" in report["patches"][0] and "spread_slid" not in report["patches"][0]
    assert paper.options["density"] == "uniform"
    assert report["moved"] == sum(p["moved"] for p in report["patches"]) > 0


def test_inputs_are_not_changed_and_outputs_are_fresh_arrays():
    slider = slider_from_files(DATA / "elbow" / "bind.obj", DATA / "elbow" / "patch.txt")
    frame = frame_positions(DATA / "elbow" / "frames" / "elbow.0005.obj")
    before = frame.copy()
    out, _ = slider.slide(frame)
    assert np.array_equal(frame, before) and not np.shares_memory(out, frame)
    # A float32 or Fortran-ordered frame is converted, to the same result.
    assert slider.slide(np.asfortranarray(frame))[0].tobytes() == out.tobytes()


def test_errors_raise_with_their_kinds(tmp_path):
    positions, face_vertices, face_sizes = skinslide.read_mesh(str(DATA / "elbow" / "bind.obj"))
    patch = skinslide.read_patch(str(DATA / "elbow" / "patch.txt"))

    def make(**kwargs):
        return skinslide.Slider(positions, face_vertices, patch, face_sizes=face_sizes, **kwargs)

    cases = [
        (lambda: make(method="paper", rotation_fits=2), skinslide.UsageError, "rotation_fits"),
        (lambda: make(density="paper"), skinslide.UsageError, "applies to method 'paper'"),
        (lambda: make(method="sideways"), skinslide.UsageError, "unknown method"),
        (lambda: make(tolerance=2.0), skinslide.UsageError, "tolerance"),
        (lambda: make(convergence=float("nan")), skinslide.UsageError, "convergence"),
        (lambda: make(solver="search", blend=1e-9), skinslide.UsageError, "below round-off"),
            (lambda: make(blend=1), skinslide.UsageError, "blend applies to solver 'search' only"),
        (lambda: make(frobnicate=1), skinslide.UsageError, "unknown option frobnicate"),
        # A misspelt keyword: the nearest one named, as the command line does (--pach).
        (lambda: make(rotation_fit=2), skinslide.UsageError,
         "unknown option rotation_fit; the nearest option is rotation_fits$"),
        (lambda: make(face_size=face_sizes), skinslide.UsageError,
         "unknown option face_size; the nearest option is face_sizes$"),
        (lambda: make(pins=[10**6]), skinslide.UsageError, "out of range"),
        (lambda: skinslide.Slider(positions, face_vertices, [10**6], face_sizes=face_sizes),
         skinslide.InputError, "out of range"),
        (lambda: make().slide(positions[:-1]), skinslide.InputError, "vertices"),
        (lambda: skinslide.read_patch(str(tmp_path / "none.txt")), skinslide.InputError,
         "cannot read"),
    ]
    for call, error, words in cases:
        with pytest.raises(error, match=words) as caught:
            call()
        assert isinstance(caught.value, skinslide.Error)
        assert caught.value.kind == error.__name__[:-len("Error")].lower()
    bad = tmp_path / "bad.txt"
    bad.write_text("1 2\nthree\n")
    with pytest.raises(skinslide.InputError, match=r"bad.txt:2"):
        skinslide.read_patch(str(bad))


def test_a_gltfs_buffers_outside_its_folder_need_allow_uri_outside(tmp_path):
    # One triangle whose buffer lies in a sibling tree: chars/tri.gltf -> ../shared/tri.bin.
    (tmp_path / "chars").mkdir()
    (tmp_path / "shared").mkdir()
    (tmp_path / "shared" / "tri.bin").write_bytes(
        np.array([0, 0, 0, 1, 0, 0, 0, 1, 0], dtype="<f4").tobytes())
    gltf = tmp_path / "chars" / "tri.gltf"
    gltf.write_text(json.dumps({
        "asset": {"version": "2.0"},
        "buffers": [{"uri": "../shared/tri.bin", "byteLength": 36}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}]}))
    with pytest.raises(skinslide.InputError, match="outside the glTF's folder"):
        skinslide.read_mesh(str(gltf))
    with pytest.raises(skinslide.InputError, match="outside the glTF's folder"):
        skinslide.read_mesh(str(gltf), allow_uri_outside=[str(tmp_path / "chars")])
    positions, face_vertices, face_sizes = skinslide.read_mesh(
        str(gltf), allow_uri_outside=[str(tmp_path / "shared")])
    assert positions.tolist() == [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
    assert face_vertices.tolist() == [0, 1, 2] and face_sizes.tolist() == [3]


def test_option_specs_declare_what_the_slider_takes():
    specs = skinslide.option_specs()
    by_name = {spec["name"]: spec for spec in specs}
    assert len(by_name) == len(specs), "one spec a name"
    assert [s["name"] for s in specs if s["method"] is None] == ["strength", "method"]
    assert by_name["method"]["choices"] == METHODS and by_name["method"]["default"] == "elastic"
    for method in METHODS:
        defaults = {s["name"]: s["default"] for s in specs if s["method"] == method}
        assert skinslide.default_options(method) == {"method": method, **defaults}
    assert by_name["density"]["choices"] == ["paper", "inverse", "uniform"]
    assert by_name["density"]["words"] == ["paper", "inverse", "length", "uniform"]
    assert by_name["q_floor"]["option"] == "--q-floor" and by_name["q_floor"]["type"] == "float"
    positions, face_vertices, face_sizes = skinslide.read_mesh(str(DATA / "elbow" / "bind.obj"))
    patch = skinslide.read_patch(str(DATA / "elbow" / "patch.txt"))
    for spec in specs:
        if spec["method"] is None or spec["type"] == "word":
            continue
        # The ends of the range are taken; past them the Slider refuses, naming the option.
        # (--ease-in counts among the rotation fits: its largest needs the most fits.)
        fits = {"rotation_fits": 1000} if spec["name"] == "ease_in" else {}
        if spec["needs"]:  # the search's internals need solver = 'search'
            fits[spec["needs"][0]] = spec["needs"][1]
        for end, past in ((spec["min"], spec["min"] - 1), (spec["max"], spec["max"] * 2)):
            skinslide.Slider(positions, face_vertices, patch, face_sizes=face_sizes,
                             method=spec["method"], **fits, **{spec["name"]: end})
            with pytest.raises(skinslide.UsageError, match=spec["name"] + " = "):
                skinslide.Slider(positions, face_vertices, patch, face_sizes=face_sizes,
                                 method=spec["method"], **fits, **{spec["name"]: past})
    with pytest.raises(skinslide.UsageError, match="--ease-in 3 leaves no rotation fit"):
        skinslide.Slider(positions, face_vertices, patch, face_sizes=face_sizes, solver="search",
                         ease_in=3)
    with pytest.raises(skinslide.UsageError, match="ease_in applies to solver 'search' only"):
        skinslide.Slider(positions, face_vertices, patch, face_sizes=face_sizes, ease_in=1)


def test_a_cache_written_by_the_module_is_the_commands(cli, tmp_path):
    """write_cache rounds each coordinate to float32 once, as the command writes a slid cache:
    the module's PC2 of the slid frames is the command's slid PC2, byte for byte; read_cache reads
    it back with its header."""
    bind, patch = DATA / "elbow" / "bind.obj", DATA / "elbow" / "patch.txt"
    cli("--patch", patch, bind, DATA / "elbow" / "elbow.pc2", "-o", tmp_path / "slid")
    shot, header = skinslide.read_cache(str(DATA / "elbow" / "elbow.pc2"))
    assert shot.dtype == np.float32 and shot.shape == (5, 1056, 3)
    assert header == {"format": "pc2", "points": 1056, "samples": 5, "frames": [1, 2, 3, 4, 5],
                      "start_frame": 1.0, "sample_rate": 1.0}
    slider = slider_from_files(bind, patch)
    slid = np.stack([slider.slide(sample.astype(np.float64))[0] for sample in shot])
    skinslide.write_cache(str(tmp_path / "module.pc2"), slid, start_frame=1)
    assert (tmp_path / "module.pc2").read_bytes() == (tmp_path / "slid" / "elbow.pc2").read_bytes()
    # MDD: times, one a sample; read back as written.
    skinslide.write_cache(str(tmp_path / "shot.mdd"), slid[:2], times=[0, 1 / 24])
    back, mdd = skinslide.read_cache(str(tmp_path / "shot.mdd"))
    assert np.array_equal(back, slid[:2].astype(np.float32))
    assert mdd["format"] == "mdd" and mdd["frames"] == [0, 1] and len(mdd["times"]) == 2


def test_cache_arguments_are_checked(tmp_path):
    frames = np.zeros((2, 4, 3))
    with pytest.raises(skinslide.UsageError, match="an MDD cache needs times"):
        skinslide.write_cache(str(tmp_path / "a.mdd"), frames)
    with pytest.raises(skinslide.UsageError, match=r"shape \(samples, points, 3\)"):
        skinslide.write_cache(str(tmp_path / "a.pc2"), np.zeros((4, 3)))
    with pytest.raises(skinslide.UsageError, match="sampleRate 0"):
        skinslide.write_cache(str(tmp_path / "a.pc2"), frames, sample_rate=0)
    with pytest.raises(skinslide.UsageError, match=".pc2 or .mdd"):
        skinslide.write_cache(str(tmp_path / "a.obj"), frames)
    with pytest.raises(skinslide.InputError):
        skinslide.read_cache(str(tmp_path / "none.pc2"))
    assert not any(tmp_path.iterdir()), "a refused cache leaves no file"
