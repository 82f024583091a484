"""The package against the CLI: the same scene and settings give the same bits."""

import csv
import threading
import time

import numpy as np
import OpenEXR
import pytest

import prismatic
from conftest import SMALL, flags

SCENE_TEXT = """
[render]
width = 40
height = 30
photons = 3000
radius = 0.03
passes = 3
seed = 7

[camera]
position = [4.2, 2.6, 3.4]
look_at = [0.4, 0.3, 0.0]
up = [0.0, 1.0, 0.0]
fov_deg = 42

[[light]]
kind = "spot"
position = [-2.5, 6.0, -0.5]
direction = [2.5, -5.0, 0.5]
cone_deg = 40
power = 38

[[object]]
shape = "sphere"
center = [0.0, 1.0, 0.0]
radius = 1.0
material = "glass"

[[object]]
shape = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "floor"

[material.glass]
kind = "dielectric"
ior = "paper"

[material.floor]
kind = "diffuse"
albedo = [0.8, 0.8, 0.8]
"""


def read_exr(path):
    """An EXR's RGB as float32 (height, width, 3), read by OpenEXR (not by prismatic)."""
    with OpenEXR.File(str(path)) as f:
        channels = f.channels()
        if "RGB" in channels:
            return np.asarray(channels["RGB"].pixels, dtype=np.float32)
        return np.stack([np.asarray(channels[c].pixels, dtype=np.float32) for c in "RGB"], axis=-1)


def same_bits(a, b):
    return a.shape == b.shape and a.dtype == b.dtype and np.array_equal(a.view(np.uint32), b.view(np.uint32))


def test_render_is_the_clis_exr_bit_for_bit(cli, tmp_path):
    cli("render", "sphere", "--passes", "3", *flags(SMALL), "-o", "cli.exr", cwd=tmp_path)
    image = prismatic.render("sphere", passes=3, progress=False, **SMALL)
    assert image.dtype == np.float32 and image.shape == (36, 48, 3)
    assert image.max() > 0.0, "a black image"
    assert same_bits(image, read_exr(tmp_path / "cli.exr"))


def test_light_tracing_is_the_clis_bit_for_bit(cli, tmp_path):
    cli("render", "caustic", "--passes", "2", *flags(SMALL), "--light-tracing", "false", "-o", "off.exr", cwd=tmp_path)
    cli("render", "caustic", "--passes", "2", *flags(SMALL), "-o", "on.exr", cwd=tmp_path)
    on = prismatic.render("caustic", passes=2, progress=False, **SMALL)
    off = prismatic.render("caustic", passes=2, light_tracing=False, progress=False, **SMALL)
    assert same_bits(on, read_exr(tmp_path / "on.exr")) and same_bits(off, read_exr(tmp_path / "off.exr"))
    assert not same_bits(on, off), "`caustic` light traces its directly seen caustic"
    with pytest.raises(prismatic.SceneError, match="True or False"):
        prismatic.render("caustic", light_tracing="yes", progress=False)


@pytest.mark.parametrize(
    "scene, passes, key, value, bad, expected",
    [
        ("prism", 1, "photon_sequence", "random", "halton", "expected sobol or random"),
        ("sphere", 2, "view_paths", "sampled", "jittered", "expected centre, hero or sampled"),
        ("lamps", 1, "white_point", "D65", "D50", "expected E or D65"),
    ],
)
def test_a_named_setting_is_the_clis_bit_for_bit(cli, tmp_path, scene, passes, key, value, bad, expected):
    flag = "--" + key.replace("_", "-")
    cli("render", scene, "--passes", str(passes), *flags(SMALL), flag, value, "-o", "set.exr", cwd=tmp_path)
    given = prismatic.render(scene, passes=passes, progress=False, **{key: value}, **SMALL)
    default = prismatic.render(scene, passes=passes, progress=False, **SMALL)
    assert same_bits(given, read_exr(tmp_path / "set.exr"))
    assert not same_bits(given, default), f"{key} = {value} is not the default"
    with pytest.raises(prismatic.SceneError, match=expected):
        prismatic.render(scene, progress=False, **{key: bad})


def test_the_environment_keywords_are_the_clis_flags(cli, tmp_path):
    cli("render", "sphere", *flags(SMALL), "--environment", "studio", "--environment-strength", "0.5",
        "--environment-rotation", "30", "--environment-lights", "8", "-o", "sky.exr", cwd=tmp_path)
    sky = prismatic.render("sphere", progress=False, environment="studio", environment_strength=0.5,
                           environment_rotation=30, environment_lights=8, **SMALL)
    assert same_bits(sky, read_exr(tmp_path / "sky.exr"))
    assert not same_bits(sky, prismatic.render("sphere", progress=False, **SMALL)), "the studio lit nothing"
    with pytest.raises(prismatic.SceneError, match=r"keyword arguments: environment_strength: the scene has no "
                       r"environment \(name one with environment\)"):
        prismatic.render("sphere", progress=False, environment_strength=2, **SMALL)
    with pytest.raises(prismatic.SceneError, match="environment: cannot read environment map"):
        prismatic.render("sphere", progress=False, environment=str(tmp_path / "missing.hdr"), **SMALL)
    with pytest.raises(prismatic.SceneError, match='environment_rotation: expected a number, not "east"'):
        prismatic.render("sphere", progress=False, environment="studio", environment_rotation="east", **SMALL)


def test_area_lights_is_the_clis_flag(cli, tmp_path):
    cli("render", "softbox", "--passes", "1", *flags(SMALL), "--area-lights", "4", "-o", "box.exr", cwd=tmp_path)
    given = prismatic.render("softbox", passes=1, progress=False, area_lights=4, **SMALL)
    default = prismatic.render("softbox", passes=1, progress=False, **SMALL)
    assert same_bits(given, read_exr(tmp_path / "box.exr"))
    assert not same_bits(given, default), "4 pieces draw the box's shadow more coarsely than its 32"
    with pytest.raises(prismatic.SceneError, match="area_lights: must be 1 to 4096"):
        prismatic.render("softbox", progress=False, area_lights=0)


def test_indirect_photons_is_the_clis_flag(cli, tmp_path):
    cli("render", "softbox", "--passes", "1", *flags(SMALL), "--indirect-photons", "5000", "-o", "gi.exr", cwd=tmp_path)
    given = prismatic.render("softbox", passes=1, progress=False, indirect_photons=5000, **SMALL)
    default = prismatic.render("softbox", passes=1, progress=False, **SMALL)
    assert same_bits(given, read_exr(tmp_path / "gi.exr"))
    assert not same_bits(given, default), "light bounced off the table lights the ball's underside"
    with pytest.raises(prismatic.SceneError, match="would not fit in memory"):
        prismatic.render("softbox", progress=False, indirect_photons=4294967295)


def test_a_scene_file_and_its_text_render_the_same(cli, tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text(SCENE_TEXT)
    cli("render", str(path), "-o", "cli.exr", cwd=tmp_path)
    from_file = prismatic.render(path, progress=False)
    from_text = prismatic.render(SCENE_TEXT, progress=False)
    assert same_bits(from_file, from_text)
    assert same_bits(from_file, read_exr(tmp_path / "cli.exr"))


def test_photons_are_the_clis_csv(cli, tmp_path):
    settings = {"photons": 3000, "backend": "cpu"}
    cli("photons", "prism", "--pass", "2", *flags(settings), "-o", "p.csv", cwd=tmp_path)
    columns = prismatic.photons("prism", pass_=2, **settings)
    with open(tmp_path / "p.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) > 100 and list(rows[0]) == list(columns)
    types = {"emission": np.uint32, "band": np.int32, "lambda_nm": np.float32, "x": np.float64,
             "y": np.float64, "z": np.float64, "dir_x": np.float32, "dir_y": np.float32,
             "dir_z": np.float32, "power": np.float32}
    for name, dtype in types.items():
        got = columns[name]
        assert got.dtype == dtype and len(got) == len(rows), name
        want = np.array([float(r[name]) if r[name] != "" else np.nan for r in rows]).astype(dtype)
        assert np.array_equal(got, want, equal_nan=dtype != np.uint32 and dtype != np.int32), name


def test_partials_merge_into_one_render_bit_for_bit_in_the_clis_format(cli, tmp_path):
    cli("render", "sphere", "--passes", "2..4", *flags(SMALL), "--partial", "b.partial", cwd=tmp_path)
    a = prismatic.render_partial("sphere", range(0, 2), **SMALL)
    b = prismatic.render_partial("sphere", (2, 4), **SMALL)
    assert b == (tmp_path / "b.partial").read_bytes(), "not the bytes of the CLI's partial file"
    merged = prismatic.merge([b, a])
    assert same_bits(merged, prismatic.render("sphere", passes=4, progress=False, **SMALL))
    with pytest.raises(prismatic.SceneError, match=r"partials\[1\]: pass 0 is in both"):
        prismatic.merge([a, a])
    other = prismatic.render_partial("sphere", (4, 5), **{**SMALL, "seed": 9})
    with pytest.raises(prismatic.SceneError, match=r"partials\[1\].*different scene or settings"):
        prismatic.merge([a, other])
    with pytest.raises(prismatic.SceneError, match="not a prismatic partial"):
        prismatic.merge([b"hello"])


def test_a_bad_scene_raises_with_its_file_line_and_key_and_writes_nothing(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(SCENE_TEXT.replace("photons = 3000", "photons = -3"))
    before = sorted(p.name for p in tmp_path.iterdir())
    with pytest.raises(prismatic.SceneError) as raised:
        prismatic.render(path, progress=False)
    e = raised.value
    assert e.file == str(path) and e.key == "render.photons" and e.line == 5, (e.file, e.key, e.line)
    assert str(e).startswith(f"{path}:5: render.photons: "), str(e)
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_bad_settings_are_named_as_keywords():
    with pytest.raises(prismatic.SceneError) as raised:
        prismatic.render("sphere", width=0, progress=False)
    assert (raised.value.file, raised.value.key) == ("keyword arguments", "width")
    with pytest.raises(prismatic.SceneError, match="bands"):
        prismatic.render("sphere", bands="paper9", progress=False)
    with pytest.raises(prismatic.SceneError, match="unknown backend"):
        prismatic.render("sphere", backend="quantum", progress=False)
    with pytest.raises(prismatic.SceneError, match="no such built-in scene or file"):
        prismatic.render("no-such-scene", progress=False)
    with pytest.raises(TypeError, match="unknown setting.*photon_count"):
        prismatic.render("sphere", photon_count=5)


def test_progress_is_called_per_pass_and_an_exception_in_it_stops_the_render():
    seen = []
    prismatic.render("sphere", passes=3, progress=lambda done, total: seen.append((done, total)), **SMALL)
    assert seen == [(1, 3), (2, 3), (3, 3)]

    def stop(done, total):
        seen.append(done)
        raise KeyboardInterrupt

    seen.clear()
    with pytest.raises(KeyboardInterrupt):
        prismatic.render("sphere", passes=50, progress=stop, **SMALL)
    assert seen == [1]


def test_a_time_budget_alone_renders_until_it_is_spent():
    seen = []
    prismatic.render("sphere", time=0.3, progress=lambda done, total: seen.append(total), **SMALL)
    assert seen and all(total is None for total in seen)


def test_the_gil_is_released_while_rendering():
    ticks = 0
    worker = threading.Thread(target=prismatic.render, args=("sphere",),
                              kwargs={"passes": 6, "progress": False, "width": 160, "height": 120, "backend": "cpu"})
    worker.start()
    start = time.perf_counter()
    while worker.is_alive():
        ticks += 1
    elapsed = time.perf_counter() - start
    worker.join()
    # Holding the GIL for the render would leave this thread a handful of
    # switch intervals (5 ms each); released, it spins freely.
    assert elapsed > 0.05 and ticks / elapsed > 50_000, (ticks, elapsed)


def test_built_in_scenes_are_listed():
    assert {"sphere", "prism", "caustic"} <= set(prismatic.scenes())
