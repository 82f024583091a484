#!/usr/bin/env python3
"""Indirect photons with one wavelength a path against several, at equal
time: two builds of the CLI render the built-in `room` (200 x 200, CPU
backend, light tracing) for 1, 2, 4, 8 and 16 s each against one long
reference rendered by the second build (both are unbiased, so the
reference serves both). Two errors per render: the relRMSE of the
per-pixel R + G + B (brightness), and the relRMSE of each of R, G and B
on its own, averaged (colour: chroma noise shows there).

    git worktree add /tmp/before <commit> && (cd /tmp/before && cargo build --release --bin prismatic)
    cargo build --release --bin prismatic
    target/python/bin/python scripts/indirect_wavelengths.py --before /tmp/before/target/release/prismatic
"""

import argparse
import subprocess
import tempfile
from pathlib import Path

import numpy as np

from exr_rgb import brightness_error, read_rgb

TIMES = (1, 2, 4, 8, 16)


def render(binary: str, seconds: float, seed: int, out: Path) -> np.ndarray:
    args = ["render", "room", "--width", "200", "--height", "200", "--backend", "cpu"]
    subprocess.run([binary, *args, "--time", str(seconds), "--seed", str(seed), "-o", str(out)], check=True,
                   capture_output=True)
    return read_rgb(out)


def colour_error(got: np.ndarray, reference: np.ndarray) -> float:
    errors = [np.sqrt(np.mean((got[..., c] - reference[..., c]) ** 2)) / np.mean(reference[..., c]) for c in range(3)]
    return float(np.mean(errors))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", required=True, help="the CLI built before the change")
    parser.add_argument("--after", default="target/release/prismatic")
    parser.add_argument("--reference-s", type=float, default=120.0)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        out = Path(scratch) / "render.exr"
        reference = render(args.after, args.reference_s, 1000, out)
        print(f"reference: {args.reference_s:g} s, mean R + G + B {reference.sum(axis=2).mean():.4f}")
        print("| build | " + " | ".join(f"{s} s" for s in TIMES) + " |")
        print("|---|" + "---|" * len(TIMES))
        for name, binary in (("before", args.before), ("after", args.after)):
            errors = [render(binary, s, 7 + k, out) for k, s in enumerate(TIMES)]
            cells = [f"{brightness_error(e, reference):.3f} / {colour_error(e, reference):.3f}" for e in errors]
            print(f"| {name} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
