#!/usr/bin/env python3
"""prismatic and LuxCore at equal error, on one machine in one run.

Five scenes, each a diffuse floor (albedo 0.8) with glass of
n(λ) = 1.5 + 0.02/λ² (λ in µm), a 400×400 camera, depth 10, 2 threads:

- `prism` (z up): issue 26's scene, a glass prism along y under a 1° spot,
  its spectrum on the floor seen from above;
- `sphere` (z up): a glass ball of radius 1 resting on the floor under a
  14° spot that covers it, its focused caustic beside it (prismatic's
  analytic sphere; LuxCore's a UV sphere of 36,864 triangles with smooth
  normals);
- `sky` (y up): the same ball raised 0.6 above the floor under an HDR
  environment, a sky (white, 0.4 at the zenith to 1 at the horizon) with a
  sun (radius 2.5°, radiance 2,000, 50° up), written by this script as one
  Radiance .hdr file that both renderers read (LuxCore's `infinite` light;
  prismatic's environment light, which shines as the suns of its median
  cut);
- `frosted` (z up): the `sphere` scene with its glass frosted, roughness
  0.3 (prismatic's GGX facets of width α = 0.09; LuxCore's `roughglass`
  with u and v roughness 0.09: its Schlick distribution of roughness u·v
  is GGX's D with α² = u·v, so its u is GGX's α), its caustic blurred
  into a glow;
- `panel` (y up): the ball resting on the floor under a light panel (an
  emissive square, 1.2 m a side, radiance 10, 4 m up and 1.5 m to the
  side, facing down): an area light's soft shadow and blurred caustic
  (LuxCore's emissive matte mesh; prismatic's area light, exact where
  unblocked and shadowed per piece).

LuxCore 2.11 (pyluxcore from PyPI) renders the spot scenes with LIGHTCPU
(light tracing with camera connections), the frosted ball with LIGHTCPU,
BIDIRCPU and PATHCPU too (behind rough glass the caustic is a glossy path,
which camera paths can find), and the sky with BIDIRCPU and
PATHCPU (the sky's and the panel's direct light wants paths from the
camera, their caustics light paths), each with its Sobol sampler; prismatic renders
through its Python package on the CPU backend in each configuration
listed in CONFIGS.

Each renderer is compared with its own converged reference (a long render
with another seed): the error is the relRMSE of the per-pixel R + G + B,
the RMSE divided by the reference's mean: over the caustic (the pixels
whose reference is above 5 % of its maximum, as
`prismatic_conformance::compare::caustic_rel_rmse`) for the spot scenes,
over the whole image for the sky. Against its own reference: prismatic's
median cut converges to its own (biased) image, and the script prints how
far the two references are apart. LuxCore's curve comes
from snapshots of one session; each of prismatic's points is a separate
render with `time=T` (passes until the time is spent), timed from the call
to the returned image. The times to reach each error are interpolated
log-log between measured points.

    python3 -m venv target/compare
    target/compare/bin/pip install ./python pyluxcore numpy
    target/compare/bin/python scripts/luxcore_compare.py [--reference-s 180] [--shortest-s 0.125] [--longest-s 32]
        [--scenes prism sphere frosted sky panel]
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import sys
import time
from dataclasses import dataclass, replace
from typing import Callable, Dict, List, Sequence, Tuple

import numpy as np
import prismatic
import pyluxcore
from sky_map import sky_texels, write_hdr

WIDTH = HEIGHT = 400
THREADS = 2
DEPTH = 10
ERRORS = (0.09, 0.05, 0.03)


@dataclass
class Setup:
    """One scene of the comparison: its lights, camera and glass in both
    renderers' terms, which way is up, and how LuxCore renders it."""
    name: str
    camera: Dict[str, object]
    prismatic_lights: str
    luxcore_lights: str
    prismatic_objects: str
    luxcore_meshes: Callable[["pyluxcore.Scene"], List[str]]
    up: Tuple[float, float, float] = (0.0, 0.0, 1.0)
    engines: Tuple[str, ...] = ("LIGHTCPU",)
    configs: Sequence[Tuple[str, Dict[str, object]]] = ()
    whole_image: bool = False
    # Settings whose own reference shows how far prismatic's default
    # approximation of the lights is from converged (printed, not tabled).
    bias_check: Dict[str, object] = None
    # The glass's roughness (0: polished): prismatic's GGX of width α = r²,
    # and LuxCore's `roughglass` with u and v roughness α (its Schlick
    # distribution D = u·v / (π (1 + (u·v − 1) cos²θ)²) is GGX's with α² = u·v).
    roughness: float = 0.0


def spot_lights(position: Tuple[float, float, float], direction: Tuple[float, float, float],
                cone_deg: float) -> Tuple[str, str]:
    """A spot of power 10 W as prismatic's scene file and LuxCore's
    properties write it. LuxCore's spot shines its `gain` as intensity
    whatever its cone, unless given a `power` (× `efficency`), which it
    spreads over its cone's solid angle as prismatic does. Its edge fades
    over `conedeltaangle` by the fourth power and its power counts half
    of that band: 0.01° is nearly prismatic's hard edge (with 0.25° the
    1° spot shone 17 % less than 10 W). With `gain = 100` and no power,
    as before 2026-11-29, the 14° spot was 1.83× too bright."""
    (x, y, z), (dx, dy, dz) = position, direction
    toml = f"""
[[light]]
kind = "spot"
position = {list(position)}
direction = {list(direction)}
cone_deg = {cone_deg}
power = 10.0
"""
    props = f"""
        scene.lights.spot.type = "spot"
        scene.lights.spot.position = {x} {y} {z}
        scene.lights.spot.target = {x + dx} {y + dy} {z + dz}
        scene.lights.spot.coneangle = {cone_deg}
        scene.lights.spot.conedeltaangle = 0.01
        scene.lights.spot.power = 10
        scene.lights.spot.efficency = 1
"""
    return toml, props


def prismatic_scene(setup: Setup) -> str:
    """The scene file prismatic renders."""
    camera = setup.camera
    return f"""
[render]
width = {WIDTH}
height = {HEIGHT}
photons = 200000
radius = 0.02
bands = 32
estimator = "density"
max_depth = {DEPTH}
ambient = 0.0
exposure = 1.0
tone_map = "clamp"

[camera]
position = {list(camera["position"])}
look_at = {list(camera["look_at"])}
up = {list(setup.up)}
fov_deg = {camera["fov_deg"]}
{setup.prismatic_lights}
[material.floor]
kind = "diffuse"
albedo = [0.8, 0.8, 0.8]

[material.glass]
kind = "dielectric"
ior = {{ cauchy = [1.5, 0.02] }}
roughness = {setup.roughness}

[[object]]
shape = "plane"
material = "floor"
point = [0.0, 0.0, 0.0]
normal = {list(setup.up)}
{setup.prismatic_objects}"""


def outward(corners: np.ndarray, faces: List[Tuple[int, int, int]]) -> List[Tuple[int, int, int]]:
    """`faces` of a convex solid wound counter-clockwise seen from outside:
    LuxCore's glass needs outward normals (inward ones render black)."""
    centre = corners.mean(axis=0)
    return [f if np.dot(np.cross(corners[f[1]] - corners[f[0]], corners[f[2]] - corners[f[0]]),
                        corners[f[0]] - centre) > 0 else (f[0], f[2], f[1]) for f in faces]


PRISM_XZ = [(-0.51978, 1.85133), (0.04223, 1.02420), (0.47754, 1.92448)]


def prism_meshes(scene: "pyluxcore.Scene") -> List[str]:
    """The prism: two end triangles, three side quads."""
    corners = np.array([(x, y, z) for y in (-1.0, 1.0) for x, z in PRISM_XZ])
    faces = [(0, 1, 2), (3, 4, 5)]
    for i in range(3):
        j = (i + 1) % 3
        faces += [(i, j, j + 3), (i, j + 3, i + 3)]
    scene.DefineMesh("glass", [tuple(c) for c in corners], outward(corners, faces), None, None, None, None)
    return ["glass"]


BALL_RINGS, BALL_SEGMENTS = 96, 192


def ball_meshes(centre: Tuple[float, float, float]) -> Callable[["pyluxcore.Scene"], List[str]]:
    """A UV sphere of radius 1 about `centre` with smooth (vertex) normals."""
    def define(scene: "pyluxcore.Scene") -> List[str]:
        normals = [(0.0, 0.0, 1.0)]
        for i in range(1, BALL_RINGS):
            theta = math.pi * i / BALL_RINGS
            for j in range(BALL_SEGMENTS):
                phi = 2 * math.pi * j / BALL_SEGMENTS
                normals.append((math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta)))
        normals.append((0.0, 0.0, -1.0))
        ring = lambda i, j: 1 + (i - 1) * BALL_SEGMENTS + j % BALL_SEGMENTS  # noqa: E731
        bottom = len(normals) - 1
        faces = [(0, ring(1, j), ring(1, j + 1)) for j in range(BALL_SEGMENTS)]
        for i in range(1, BALL_RINGS - 1):
            for j in range(BALL_SEGMENTS):
                faces += [(ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)),
                          (ring(i, j), ring(i + 1, j + 1), ring(i, j + 1))]
        faces += [(ring(BALL_RINGS - 1, j), bottom, ring(BALL_RINGS - 1, j + 1)) for j in range(BALL_SEGMENTS)]
        points = np.array(normals) + np.array(centre)
        scene.DefineMesh("glass", [tuple(p) for p in points], outward(points, faces), normals, None, None, None)
        return ["glass"]
    return define


def ball_object(centre: Tuple[float, float, float]) -> str:
    """prismatic's analytic ball of radius 1 about `centre`."""
    return f"""
[[object]]
shape = "sphere"
material = "glass"
center = {list(centre)}
radius = 1.0
"""


SKY_FILE = os.path.abspath(os.path.join("target", "luxcore-compare-sky.hdr"))
SKY_BALL = (0.0, 1.6, 0.0)
# LuxCore's infinite light maps its local +z to the zenith; this turns it to +y.
LUX_SKY_TRANSFORM = "1 0 0 0  0 0 -1 0  0 1 0 0  0 0 0 1"

SPOTS = {
    "prism": spot_lights((-4.11688, 0.0, 4.75578), (0.81915, 0.0, -0.57358), 1.0),
    "sphere": spot_lights((-3.0, 0.0, 5.0), (0.6, 0.0, -0.8), 14.0),
}

# prismatic's configurations: (label, settings); 200,000 photons a pass
# unless they say. Each is measured against the reference below rendered
# with the configuration's own view paths (sampled view paths converge to
# the box-filtered pixel, hero and centre rays to the pixel's centre).
CONFIGS: List[Tuple[str, Dict[str, object]]] = [
    ("light tracing, Sobol, 32 bands hero",
     {"light_tracing": True, "photon_sequence": "sobol", "wavelengths": "hero"}),
    ("light tracing, Sobol, 32 bands hero, 50k-photon passes",
     {"light_tracing": True, "photon_sequence": "sobol", "wavelengths": "hero", "photons": 50000}),
    ("light tracing, Sobol, 32 bands hero, sampled view, 50k-photon passes",
     {"light_tracing": True, "photon_sequence": "sobol", "wavelengths": "hero", "photons": 50000,
      "view_paths": "sampled"}),
    ("light tracing, Sobol, 32 bands continuous",
     {"light_tracing": True, "photon_sequence": "sobol", "wavelengths": "continuous"}),
    ("light tracing, random, 32 bands continuous",
     {"light_tracing": True, "photon_sequence": "random", "wavelengths": "continuous"}),
    ("gather, random, 32 bands continuous (last wave)",
     {"light_tracing": False, "photon_sequence": "random", "wavelengths": "continuous"}),
]
PRISMATIC_REFERENCE = {"light_tracing": True, "photon_sequence": "sobol", "wavelengths": "hero", "bands": 64}

SETUPS = {
    "prism": Setup(
        name="prism",
        camera={"position": (2.2, -3.2, 2.4), "look_at": (0.52, 0.0, 0.0), "fov_deg": 16.0},
        prismatic_lights=SPOTS["prism"][0],
        luxcore_lights=SPOTS["prism"][1],
        prismatic_objects=f"""
[[object]]
shape = "prism"
material = "glass"
vertices = {[[x, -1.0, z] for x, z in PRISM_XZ]}
extrude = [0.0, 2.0, 0.0]
""",
        luxcore_meshes=prism_meshes,
        configs=CONFIGS,
    ),
    "sphere": Setup(
        name="sphere",
        camera={"position": (4.5, -3.5, 3.5), "look_at": (0.5, 0.0, 0.4), "fov_deg": 30.0},
        prismatic_lights=SPOTS["sphere"][0],
        luxcore_lights=SPOTS["sphere"][1],
        prismatic_objects=ball_object((0.0, 0.0, 1.0)),
        luxcore_meshes=ball_meshes((0.0, 0.0, 1.0)),
        configs=CONFIGS,
    ),
    "sky": Setup(
        name="sky",
        camera={"position": (5.0, 4.0, 5.0), "look_at": (0.0, 0.6, 0.0), "fov_deg": 40.0},
        prismatic_lights=f"""
[[light]]
kind = "environment"
map = "{SKY_FILE}"
""",
        luxcore_lights=f"""
        scene.lights.sky.type = "infinite"
        scene.lights.sky.file = "{SKY_FILE}"
        scene.lights.sky.gamma = 1.0
        scene.lights.sky.gain = 1 1 1
        scene.lights.sky.transformation = {LUX_SKY_TRANSFORM}
""",
        prismatic_objects=ball_object(SKY_BALL),
        luxcore_meshes=ball_meshes(SKY_BALL),
        up=(0.0, 1.0, 0.0),
        engines=("BIDIRCPU", "PATHCPU"),
        configs=CONFIGS[:1] + CONFIGS[-1:],
        whole_image=True,
    ),
}

# The sphere's ball frosted: the same scene but for the glass's roughness.
SETUPS["frosted"] = replace(SETUPS["sphere"], name="frosted", engines=("LIGHTCPU", "BIDIRCPU", "PATHCPU"),
                            configs=CONFIGS[:2], roughness=0.3)


# The panel: a square of radiance PANEL_RADIANCE facing down (wound so
# that (b − a) × (c − a) points down in both renderers).
PANEL_CORNERS = [(-2.1, 4.0, -0.6), (-0.9, 4.0, -0.6), (-0.9, 4.0, 0.6), (-2.1, 4.0, 0.6)]
PANEL_TRIANGLES = [(0, 1, 2), (0, 2, 3)]
PANEL_RADIANCE = 10.0
PANEL_BALL = (0.0, 1.0, 0.0)


def panel_meshes(scene: "pyluxcore.Scene") -> List[str]:
    """The ball (the glass) and the panel (lit in `luxcore_lights`)."""
    scene.DefineMesh("panel", PANEL_CORNERS, PANEL_TRIANGLES, None, None, None, None)
    return ball_meshes(PANEL_BALL)(scene)


SETUPS["panel"] = Setup(
    name="panel",
    camera={"position": (5.0, 3.5, 5.0), "look_at": (-0.3, 0.6, 0.0), "fov_deg": 40.0},
    prismatic_lights=f"""
[material.panel]
kind = "diffuse"
albedo = [0.8, 0.8, 0.8]
emission = [{PANEL_RADIANCE}, {PANEL_RADIANCE}, {PANEL_RADIANCE}]

[[object]]
shape = "mesh"
material = "panel"
positions = {[list(c) for c in PANEL_CORNERS]}
triangles = {[list(t) for t in PANEL_TRIANGLES]}
""",
    luxcore_lights=f"""
        scene.materials.panel.type = "matte"
        scene.materials.panel.kd = 0.8 0.8 0.8
        scene.materials.panel.emission = {PANEL_RADIANCE} {PANEL_RADIANCE} {PANEL_RADIANCE}
        scene.objects.panel.shape = "panel"
        scene.objects.panel.material = "panel"
""",
    prismatic_objects=ball_object(PANEL_BALL),
    luxcore_meshes=panel_meshes,
    up=(0.0, 1.0, 0.0),
    engines=("BIDIRCPU", "PATHCPU"),
    configs=CONFIGS[:1] + CONFIGS[-1:],
    whole_image=True,
    bias_check={"area_lights": 1024},
)


def rel_rmse(got: np.ndarray, reference: np.ndarray, whole_image: bool) -> float:
    """relRMSE of the per-pixel R + G + B: over the whole image, or over
    the reference's caustic (its pixels above 5 % of its maximum)."""
    g, r = got.sum(axis=2).ravel(), reference.sum(axis=2).ravel()
    mask = np.ones_like(r, dtype=bool) if whole_image else r > 0.05 * r.max()
    return float(np.sqrt(np.mean((g[mask] - r[mask]) ** 2)) / np.mean(r[mask]))


def time_to(points: Sequence[Tuple[float, float]], target: float) -> float:
    """The time at which the (time, error) curve first reaches `target`, log-log interpolated (inf if never)."""
    for (t0, e0), (t1, e1) in zip(points, points[1:]):
        if e1 <= target < e0:
            f = (math.log(e0) - math.log(target)) / (math.log(e0) - math.log(e1))
            return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
    if points and points[0][1] <= target:
        return points[0][0]
    return math.inf


def prismatic_render(setup: Setup, seconds: float, seed: int, settings: Dict[str, object]) -> Tuple[np.ndarray, float]:
    """A render of `seconds` (passes until spent); the image and the call's wall time."""
    t = time.perf_counter()
    scene = prismatic_scene(setup)
    image = prismatic.render(scene, time=seconds, seed=seed, backend="cpu", progress=False, **settings)
    return image, time.perf_counter() - t


def luxcore_scene(setup: Setup) -> "pyluxcore.Scene":
    scene = pyluxcore.Scene()
    if setup.up == (0.0, 0.0, 1.0):
        floor = [(-10, -10, 0), (10, -10, 0), (10, 10, 0), (-10, 10, 0)]
    else:
        # Under a sky the floor must reach the horizon, as prismatic's plane does.
        floor = [(-1000, 0, -1000), (-1000, 0, 1000), (1000, 0, 1000), (1000, 0, -1000)]
    scene.DefineMesh("floor", floor, [(0, 1, 2), (0, 2, 3)], None, None, None, None)
    glass = setup.luxcore_meshes(scene)
    cx, cy, cz = setup.camera["position"]
    tx, ty, tz = setup.camera["look_at"]
    ux, uy, uz = setup.up
    objects = "\n".join(f'scene.objects.{m}.shape = "{m}"\nscene.objects.{m}.material = "glass"' for m in glass)
    alpha = setup.roughness ** 2
    glass_type = f'"roughglass"\nscene.materials.glass.uroughness = {alpha}\nscene.materials.glass.vroughness = {alpha}' \
        if alpha > 0 else '"glass"'
    props = pyluxcore.Properties()
    props.SetFromString(f"""
        scene.camera.type = "perspective"
        scene.camera.lookat.orig = {cx} {cy} {cz}
        scene.camera.lookat.target = {tx} {ty} {tz}
        scene.camera.up = {ux} {uy} {uz}
        scene.camera.fieldofview = {setup.camera["fov_deg"]}
        scene.materials.matte.type = "matte"
        scene.materials.matte.kd = 0.8 0.8 0.8
        scene.materials.glass.type = {glass_type}
        scene.materials.glass.kr = 1 1 1
        scene.materials.glass.kt = 1 1 1
        scene.materials.glass.interiorior = 1.5
        scene.materials.glass.cauchyb = 0.02
        scene.objects.floor.shape = "floor"
        scene.objects.floor.material = "matte"
        {objects}
        {setup.luxcore_lights}
        """)
    scene.Parse(props)
    return scene


# Each engine's own settings: LIGHTCPU traces from the lights and connects
# to the camera; BIDIRCPU joins both; PATHCPU with hybrid back/forward
# tracing (LuxCore 2.5+) adds light paths for the caustics to its camera
# paths.
ENGINE_PROPS = {
    "LIGHTCPU": f"light.maxdepth = {DEPTH}\npath.maxdepth = {DEPTH}",
    "BIDIRCPU": f"light.maxdepth = {DEPTH}\npath.maxdepth = {DEPTH}",
    "PATHCPU": f"path.pathdepth.total = {DEPTH}\npath.pathdepth.diffuse = {DEPTH}\n"
               f"path.pathdepth.specular = {DEPTH}\npath.hybridbackforward.enable = 1",
}


def luxcore_curve(setup: Setup, engine: str, seconds: float, seed: int,
                  snapshots: Sequence[float]) -> Tuple[List[Tuple[float, np.ndarray]], str]:
    """One session of `engine` for `seconds`: its linear RGB at each snapshot time, and its sample rate."""
    props = pyluxcore.Properties()
    props.SetFromString(f"""
        renderengine.type = "{engine}"
        sampler.type = "SOBOL"
        renderengine.seed = {seed}
        {ENGINE_PROPS[engine]}
        native.threads.count = {THREADS}
        film.width = {WIDTH}
        film.height = {HEIGHT}
        film.imagepipelines.0.0.type = "TONEMAP_LINEAR"
        film.imagepipelines.0.0.scale = 1.0
        film.outputs.0.type = "RGB_IMAGEPIPELINE"
        film.outputs.0.filename = "unused.exr"
        batch.halttime = {seconds + 5}
        """)
    config = pyluxcore.RenderConfig(props, luxcore_scene(setup))
    session = pyluxcore.RenderSession(config)
    buffer = np.zeros((HEIGHT, WIDTH, 3), dtype=np.float32)
    out = []
    session.Start()
    start = time.perf_counter()
    for at in snapshots:
        while time.perf_counter() - start < at:
            time.sleep(0.005)
        elapsed = time.perf_counter() - start
        session.UpdateStats()
        film = session.GetFilm()
        film.GetOutputFloat(pyluxcore.FilmOutputType.RGB_IMAGEPIPELINE, buffer)
        out.append((elapsed, np.flipud(buffer).copy()))  # LuxCore's rows run bottom up
    stats = session.GetStats()
    rate = f"{stats.Get('stats.renderengine.total.samplesec').GetFloat() / 1e6:.2f} M samples/s"
    session.Stop()
    return out, rate


def row(label: str, points: List[Tuple[float, float]]) -> str:
    cells = []
    reached = min(e for _, e in points)
    for target in ERRORS:
        t = time_to(points, target)
        cells.append(f"{t:.2f} s" if math.isfinite(t) else f"not in {points[-1][0]:.0f} s ({reached:.3f})")
    return f"| {label} | " + " | ".join(cells) + " |"


def compare(setup: Setup, reference_s: float, budgets: List[float]) -> List[str]:
    """Both renderers on `setup`: the table's rows."""
    rows = []
    error = lambda image, reference: rel_rmse(image, reference, setup.whole_image)  # noqa: E731
    lux_references = {}
    for engine in setup.engines:
        lux_references[engine] = luxcore_curve(setup, engine, reference_s, 1000, [reference_s])[0][-1][1]
        lux, rate = luxcore_curve(setup, engine, budgets[-1], 1, budgets)
        lux_points = [(t, error(image, lux_references[engine])) for t, image in lux]
        print(f"{setup.name}: LuxCore {engine} ({rate}): " + ", ".join(f"{t:.1f} s {e:.4f}" for t, e in lux_points))
        rows.append(row(f"LuxCore {engine}, Sobol", lux_points))

    references: Dict[str, np.ndarray] = {}
    for label, settings in setup.configs:
        view = str(settings.get("view_paths", "hero"))  # prismatic's default
        if view not in references:
            references[view] = prismatic_render(setup, reference_s, 1000,
                                                 {**PRISMATIC_REFERENCE, "view_paths": view})[0]
        points = []
        for budget in budgets:
            image, took = prismatic_render(setup, budget, 1, settings)
            points.append((took, error(image, references[view])))
        print(f"{setup.name}: prismatic, {label}: " + ", ".join(f"{t:.1f} s {e:.4f}" for t, e in points))
        rows.append(row(f"prismatic, {label}", points))
    if setup.bias_check and "hero" in references:
        finer = prismatic_render(setup, reference_s, 1000, {**PRISMATIC_REFERENCE, **setup.bias_check})[0]
        print(f"{setup.name}: prismatic's reference against one with {setup.bias_check}: relRMSE "
              f"{rel_rmse(references['hero'], finer, True):.4f}, means {references['hero'].mean():.4f} and "
              f"{finer.mean():.4f}")
    # How far the two renderers' references are apart: their means, and the
    # relRMSE of 8×8-pixel blocks with the sun's glints through the glass
    # clipped (a few pixels at the sun's radiance would be all of it, and
    # pixel-centre view paths catch other glints than supersampled pixels).
    ours = references.get("hero")
    for engine, lux_reference in lux_references.items():
        if ours is None:
            break
        blocks = [np.minimum(x, GLINT_CLIP).reshape(HEIGHT // 8, 8, WIDTH // 8, 8, 3).mean(axis=(1, 3))
                  for x in (ours, lux_reference)]
        print(f"{setup.name}: references, prismatic against LuxCore {engine}: means {ours.mean():.4f} and "
              f"{lux_reference.mean():.4f}; 8×8 blocks, glints clipped: relRMSE {rel_rmse(*blocks, True):.4f}")
    return rows


# Radiance above which a pixel counts as a glint of the sun (the sky and the
# floor stay below 10).
GLINT_CLIP = 30.0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--reference-s", type=float, default=180.0, help="seconds of each reference render")
    parser.add_argument("--shortest-s", type=float, default=0.125, help="the shortest measured render (seconds)")
    parser.add_argument("--longest-s", type=float, default=32.0, help="the longest measured render (seconds)")
    parser.add_argument("--scenes", nargs="+", choices=sorted(SETUPS), default=["prism", "sphere", "frosted", "sky", "panel"])
    args = parser.parse_args()
    pyluxcore.Init(lambda _: None)
    if "sky" in args.scenes:
        os.makedirs(os.path.dirname(SKY_FILE), exist_ok=True)
        write_hdr(SKY_FILE, sky_texels())
    budgets = [args.shortest_s * 2 ** k for k in range(int(math.log2(args.longest_s / args.shortest_s)) + 1)]
    print(f"# {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs; "
          f"prismatic {prismatic.__version__}, LuxCore {pyluxcore.Version()}, {THREADS} threads each")
    print(f"references: {args.reference_s:.0f} s each; renders of {budgets} s")
    tables = {name: compare(SETUPS[name], args.reference_s, budgets) for name in args.scenes}
    for name, rows in tables.items():
        print(f"\n{name}\n\n| renderer, settings | " + " | ".join(f"to relRMSE {e}" for e in ERRORS) + " |")
        print("|---|" + "---:|" * len(ERRORS))
        print("\n".join(rows))
    # pyluxcore 2.11's threads call into Python while the interpreter shuts
    # down (a segfault after the output): leave without finalising it.
    sys.stdout.flush()
    os._exit(0)


if __name__ == "__main__":
    main()
