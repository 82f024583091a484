#!/usr/bin/env python3
"""An environment's suns fixed along the median cut against suns drawn
anew each pass, at equal time: two builds of the CLI render a glass ball
over a floor under the sky of `sky_map.py` (a white sky with a sun, the
LuxCore comparison's `sky` scene at 200 x 200, CPU backend, the default
settings) for 1 to 32 s each. Both are measured against one long render
of the second build, whose drawn suns converge to the map's own light;
the first build's own long render shows the bias its fixed suns keep.
The error is the relRMSE of the per-pixel R + G + B over the whole image.

Any two builds compare the same way (`--before-label`, `--after-label`
name their rows). Builds whose passes cost the same (drawn suns without
and with their control variate) compare at equal passes instead
(`--passes`: 1 to 32 passes, the RMS of four seeds' errors, against a
1,024-pass render), and `--ball diffuse` makes the ball a diffuse one,
so that the sky's direct light and shadows are the image, not the
glass's caustic.

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
PASSES = (1, 2, 4, 8, 16, 32)
SEEDS = (1, 2, 3, 4)

BALLS = {
    "glass": 'kind = "dielectric"\nior = { cauchy = [1.5, 0.02] }',
    "diffuse": 'kind = "diffuse"\nalbedo = [0.7, 0.5, 0.3]',
}


def scene(sky: Path, ball: str = "glass") -> str:
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

[material.ball]
{BALLS[ball]}

[[object]]
shape = "plane"
material = "floor"
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]

[[object]]
shape = "sphere"
material = "ball"
center = [0.0, 1.6, 0.0]
radius = 1.0
"""


def render(binary: str, scene_file: Path, budget: tuple[str, float], seed: int, out: Path) -> np.ndarray:
    flag, amount = budget
    args = ["render", str(scene_file), "--backend", "cpu", flag, f"{amount:g}", "--seed", str(seed)]
    subprocess.run([binary, *args, "-o", str(out)], check=True, capture_output=True)
    return read_rgb(out)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", required=True, help="the CLI built with fixed suns")
    parser.add_argument("--after", default="target/release/prismatic")
    parser.add_argument("--reference-s", type=float, default=120.0)
    parser.add_argument("--before-label", default="fixed (before)")
    parser.add_argument("--after-label", default="drawn each pass")
    parser.add_argument("--passes", action="store_true", help="at equal passes, not equal time")
    parser.add_argument("--ball", choices=sorted(BALLS), default="glass")
    args = parser.parse_args()
    long = ("--passes", 1024) if args.passes else ("--time", args.reference_s)
    with tempfile.TemporaryDirectory() as scratch:
        sky, scene_file, out = Path(scratch) / "sky.hdr", Path(scratch) / "sky.toml", Path(scratch) / "render.exr"
        write_hdr(str(sky), sky_texels())
        scene_file.write_text(scene(sky, args.ball))
        reference = render(args.after, scene_file, long, 1000, out)
        own = render(args.before, scene_file, long, 1000, out)
        print(f"reference ({args.after_label}): {long[0]} {long[1]:g}, mean R + G + B {reference.sum(axis=2).mean():.4f}")
        print(f"{args.before_label}'s own {long[0]} {long[1]:g} render: mean {own.sum(axis=2).mean():.4f}, "
              f"relRMSE {brightness_error(own, reference):.4f} from the reference")
        steps = [("--passes", p) for p in PASSES] if args.passes else [("--time", t) for t in TIMES]
        unit = "passes" if args.passes else "s"
        print("| suns | " + " | ".join(f"{amount} {unit}" for _, amount in steps) + " |")
        print("|---|" + "---:|" * len(steps))
        for label, binary in ((args.before_label, args.before), (args.after_label, args.after)):
            errors = []
            for step in steps:
                seeds = SEEDS if args.passes else (7,)
                each = [brightness_error(render(binary, scene_file, step, seed, out), reference) for seed in seeds]
                errors.append(float(np.sqrt(np.mean(np.square(each)))))
            print(f"| {label} | " + " | ".join(f"{e:.4f}" for e in errors) + " |")


if __name__ == "__main__":
    main()
