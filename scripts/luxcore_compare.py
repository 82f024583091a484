#!/usr/bin/env python3
"""prismatic and LuxCore at equal error, on one machine in one run.

The scene is issue 26's prism (z up): a diffuse floor (albedo 0.8), a glass
prism along y with n(λ) = 1.5 + 0.02/λ² (λ in µm), a 1° spot light, a
400×400 camera with a 16° vertical field of view, depth 10, 2 threads.
LuxCore 2.11 (pyluxcore from PyPI) renders it with LIGHTCPU (light tracing
with camera connections) and its Sobol sampler; prismatic renders it
through its Python package on the CPU backend in each configuration listed
in CONFIGS.

Each renderer is compared with its own converged reference (a long render
with another seed): the error is the relRMSE over the caustic, the RMSE of
the per-pixel R + G + B over the pixels whose reference is above 5 % of
its maximum, divided by the reference's mean there (as
`prismatic_conformance::compare::caustic_rel_rmse`). LuxCore's curve comes
from snapshots of one session; each of prismatic's points is a separate
render with `time=T` (passes until the time is spent), timed from the call
to the returned image. The times to reach each error are interpolated
log-log between measured points.

    python3 -m venv target/compare
    target/compare/bin/pip install ./python pyluxcore numpy
    target/compare/bin/python scripts/luxcore_compare.py [--reference-s 180] [--longest-s 32]
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import time
from typing import Dict, List, Sequence, Tuple

import numpy as np
import prismatic
import pyluxcore

WIDTH = HEIGHT = 400
THREADS = 2
DEPTH = 10
PRISM_XZ = [(-0.51978, 1.85133), (0.04223, 1.02420), (0.47754, 1.92448)]
SPOT = {"position": (-4.11688, 0.0, 4.75578), "direction": (0.81915, 0.0, -0.57358), "cone_deg": 1.0}
CAMERA = {"position": (2.2, -3.2, 2.4), "look_at": (0.52, 0.0, 0.0), "fov_deg": 16.0}
ERRORS = (0.09, 0.05, 0.03)

PRISMATIC_SCENE = f"""
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

[camera]
position = {list(CAMERA["position"])}
look_at = {list(CAMERA["look_at"])}
up = [0.0, 0.0, 1.0]
fov_deg = {CAMERA["fov_deg"]}

[[light]]
kind = "spot"
position = {list(SPOT["position"])}
direction = {list(SPOT["direction"])}
cone_deg = {SPOT["cone_deg"]}
power = 10.0

[material.floor]
kind = "diffuse"
albedo = [0.8, 0.8, 0.8]

[material.glass]
kind = "dielectric"
ior = {{ cauchy = [1.5, 0.02] }}

[[object]]
shape = "plane"
material = "floor"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[object]]
shape = "prism"
material = "glass"
vertices = {[[x, -1.0, z] for x, z in PRISM_XZ]}
extrude = [0.0, 2.0, 0.0]
"""

# prismatic's configurations: (label, settings). The reference is the
# first's estimator with 64 bands and continuous wavelengths.
CONFIGS: List[Tuple[str, Dict[str, object]]] = [
    ("light tracing, Sobol, 32 bands continuous (this wave)",
     {"light_tracing": True, "photon_sequence": "sobol", "wavelengths": "continuous"}),
    ("light tracing, random, 32 bands continuous",
     {"light_tracing": True, "photon_sequence": "random", "wavelengths": "continuous"}),
    ("gather, random, 32 bands continuous (last wave)",
     {"light_tracing": False, "photon_sequence": "random", "wavelengths": "continuous"}),
]
PRISMATIC_REFERENCE = {"light_tracing": True, "photon_sequence": "sobol", "wavelengths": "continuous", "bands": 64}


def caustic_rel_rmse(got: np.ndarray, reference: np.ndarray) -> float:
    """relRMSE of the per-pixel R + G + B over the reference's caustic."""
    g, r = got.sum(axis=2).ravel(), reference.sum(axis=2).ravel()
    mask = r > 0.05 * r.max()
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


def prismatic_render(seconds: float, seed: int, settings: Dict[str, object]) -> Tuple[np.ndarray, float]:
    """A render of `seconds` (passes until spent); the image and the call's wall time."""
    t = time.perf_counter()
    image = prismatic.render(PRISMATIC_SCENE, time=seconds, seed=seed, backend="cpu", progress=False, **settings)
    return image, time.perf_counter() - t


def luxcore_scene() -> "pyluxcore.Scene":
    scene = pyluxcore.Scene()
    # The floor (a 20 × 20 quad) and the prism (two end triangles, three side quads).
    scene.DefineMesh("floor", [(-10, -10, 0), (10, -10, 0), (10, 10, 0), (-10, 10, 0)], [(0, 1, 2), (0, 2, 3)],
                     None, None, None, None)
    corners = np.array([(x, y, z) for y in (-1.0, 1.0) for x, z in PRISM_XZ])
    faces = [(0, 1, 2), (3, 4, 5)]
    for i in range(3):
        j = (i + 1) % 3
        faces += [(i, j, j + 3), (i, j + 3, i + 3)]
    # Wound counter-clockwise seen from outside: glass needs outward normals.
    centre = corners.mean(axis=0)
    faces = [f if np.dot(np.cross(corners[f[1]] - corners[f[0]], corners[f[2]] - corners[f[0]]),
                        corners[f[0]] - centre) > 0 else (f[0], f[2], f[1]) for f in faces]
    scene.DefineMesh("prism", [tuple(c) for c in corners], faces, None, None, None, None)
    x, y, z = SPOT["position"]
    dx, dy, dz = SPOT["direction"]
    cx, cy, cz = CAMERA["position"]
    tx, ty, tz = CAMERA["look_at"]
    props = pyluxcore.Properties()
    props.SetFromString(f"""
        scene.camera.type = "perspective"
        scene.camera.lookat.orig = {cx} {cy} {cz}
        scene.camera.lookat.target = {tx} {ty} {tz}
        scene.camera.up = 0 0 1
        scene.camera.fieldofview = {CAMERA["fov_deg"]}
        scene.materials.matte.type = "matte"
        scene.materials.matte.kd = 0.8 0.8 0.8
        scene.materials.glass.type = "glass"
        scene.materials.glass.kr = 1 1 1
        scene.materials.glass.kt = 1 1 1
        scene.materials.glass.interiorior = 1.5
        scene.materials.glass.cauchyb = 0.02
        scene.objects.floor.shape = "floor"
        scene.objects.floor.material = "matte"
        scene.objects.prism.shape = "prism"
        scene.objects.prism.material = "glass"
        scene.lights.spot.type = "spot"
        scene.lights.spot.position = {x} {y} {z}
        scene.lights.spot.target = {x + dx} {y + dy} {z + dz}
        scene.lights.spot.coneangle = {SPOT["cone_deg"]}
        scene.lights.spot.conedeltaangle = 0.25
        scene.lights.spot.gain = 100 100 100
        """)
    scene.Parse(props)
    return scene


def luxcore_curve(seconds: float, seed: int, snapshots: Sequence[float]) -> Tuple[List[Tuple[float, np.ndarray]], str]:
    """One LIGHTCPU session of `seconds`: its linear RGB at each snapshot time, and its sample rate."""
    props = pyluxcore.Properties()
    props.SetFromString(f"""
        renderengine.type = "LIGHTCPU"
        sampler.type = "SOBOL"
        renderengine.seed = {seed}
        light.maxdepth = {DEPTH}
        path.maxdepth = {DEPTH}
        native.threads.count = {THREADS}
        film.width = {WIDTH}
        film.height = {HEIGHT}
        film.imagepipelines.0.0.type = "TONEMAP_LINEAR"
        film.imagepipelines.0.0.scale = 1.0
        film.outputs.0.type = "RGB_IMAGEPIPELINE"
        film.outputs.0.filename = "unused.exr"
        batch.halttime = {seconds + 5}
        """)
    config = pyluxcore.RenderConfig(props, luxcore_scene())
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
        out.append((elapsed, buffer.copy()))
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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--reference-s", type=float, default=180.0, help="seconds of each reference render")
    parser.add_argument("--longest-s", type=float, default=32.0, help="the longest measured render (seconds)")
    args = parser.parse_args()
    pyluxcore.Init(lambda _: None)
    budgets = [0.5 * 2 ** k for k in range(int(math.log2(args.longest_s / 0.5)) + 1)]
    print(f"# {platform.processor() or platform.machine()}, {os.cpu_count()} CPUs; "
          f"prismatic {prismatic.__version__}, LuxCore {pyluxcore.Version()}, {THREADS} threads each")
    print(f"references: {args.reference_s:.0f} s each; renders of {budgets} s")

    lux_reference = luxcore_curve(args.reference_s, 1000, [args.reference_s])[0][-1][1]
    lux, rate = luxcore_curve(budgets[-1], 1, budgets)
    lux_points = [(t, caustic_rel_rmse(image, lux_reference)) for t, image in lux]
    print(f"LuxCore LIGHTCPU ({rate}): " + ", ".join(f"{t:.1f} s {e:.4f}" for t, e in lux_points))

    reference, _ = prismatic_render(args.reference_s, 1000, PRISMATIC_REFERENCE)
    rows = [row("LuxCore LIGHTCPU, Sobol", lux_points)]
    for label, settings in CONFIGS:
        points = []
        for budget in budgets:
            image, took = prismatic_render(budget, 1, settings)
            points.append((took, caustic_rel_rmse(image, reference)))
        print(f"prismatic, {label}: " + ", ".join(f"{t:.1f} s {e:.4f}" for t, e in points))
        rows.append(row(f"prismatic, {label}", points))

    print("\n| renderer, settings | " + " | ".join(f"to relRMSE {e}" for e in ERRORS) + " |")
    print("|---|" + "---:|" * len(ERRORS))
    print("\n".join(rows))


if __name__ == "__main__":
    main()
