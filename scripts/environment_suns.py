#!/usr/bin/env python3
"""An environment's suns fixed along the median cut against suns drawn
anew each pass, at equal time: two builds of the CLI render a glass ball
over a floor under the sky of `sky_map.py` (a white sky with a sun, the
LuxCore comparison's `sky` scene at 200 x 200, CPU backend, the default
settings) for 1 to 32 s each. Both are measured against one long render
of the second build, whose drawn suns converge to the map's own light;
the first build's own long render shows the bias its fixed suns keep.
The error is the relRMSE of the per-pixel R + G + B over the whole image.

    git worktree add /tmp/before <commit> && (cd /tmp/before && cargo build --release --bin prismatic)
    cargo build --release --bin prismatic
    target/python/bin/python scripts/environment_suns.py --before /tmp/before/target/release/prismatic
"""

import argparse
import subprocess
import tempfile
from pathlib import Path

import numpy as np

from exr_rgb import brightness_error, read_rgb
from sky_map import sky_texels, write_hdr

TIMES = (1, 2, 4, 8, 16, 32)


def scene(sky: Path) -> str:
    return f"""
[render]
width = 200
height = 200
max_depth = 10
ambient = 0.0

[camera]
position = [5.0, 4.0, 5.0]
look_at = [0.0, 0.6, 0.0]
up = [0.0, 1.0, 0.0]
fov_deg = 40.0

[[light]]
kind = "environment"
map = "{sky}"

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
normal = [0.0, 1.0, 0.0]

[[object]]
shape = "sphere"
material = "glass"
center = [0.0, 1.6, 0.0]
radius = 1.0
"""


def render(binary: str, scene_file: Path, seconds: float, seed: int, out: Path) -> np.ndarray:
    args = ["render", str(scene_file), "--backend", "cpu", "--time", str(seconds), "--seed", str(seed)]
    subprocess.run([binary, *args, "-o", str(out)], check=True, capture_output=True)
    return read_rgb(out)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", required=True, help="the CLI built with fixed suns")
    parser.add_argument("--after", default="target/release/prismatic")
    parser.add_argument("--reference-s", type=float, default=120.0)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        sky, scene_file, out = Path(scratch) / "sky.hdr", Path(scratch) / "sky.toml", Path(scratch) / "render.exr"
        write_hdr(str(sky), sky_texels())
        scene_file.write_text(scene(sky))
        reference = render(args.after, scene_file, args.reference_s, 1000, out)
        own = render(args.before, scene_file, args.reference_s, 1000, out)
        print(f"reference (drawn suns): {args.reference_s:g} s, mean R + G + B {reference.sum(axis=2).mean():.4f}")
        print(f"fixed suns' own {args.reference_s:g} s render: mean {own.sum(axis=2).mean():.4f}, "
              f"relRMSE {brightness_error(own, reference):.4f} from the reference")
        print("| suns | " + " | ".join(f"{s} s" for s in TIMES) + " |")
        print("|---|" + "---:|" * len(TIMES))
        for label, binary in (("fixed (before)", args.before), ("drawn each pass", args.after)):
            errors = [brightness_error(render(binary, scene_file, s, 7, out), reference) for s in TIMES]
            print(f"| {label} | " + " | ".join(f"{e:.4f}" for e in errors) + " |")


if __name__ == "__main__":
    main()
