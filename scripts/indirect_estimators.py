#!/usr/bin/env python3
"""Indirect light's two estimators at equal error: light tracing (each
photon connected to the camera) against the progressive gather (photons
within a shrinking radius of each visible point), on the built-in `room`
(a Cornell box lit by its ceiling lamp, 200 × 200).

Each estimator renders for 1, 2, 4, 8 and 16 s (the CPU backend, its own
seeds) and is compared with one long light-traced reference: the relRMSE
of the per-pixel R + G + B over the whole image (RMSE over the
reference's mean). The gather's own long render is compared with the same
reference, to show that both converge to one image (the gather's radius
bias is the part that remains).

    target/python/bin/python scripts/indirect_estimators.py [--reference-s 120]
"""

import argparse
import time

import numpy as np
import prismatic

SIZE = {"width": 200, "height": 200}
TIMES = (1.0, 2.0, 4.0, 8.0, 16.0)
ESTIMATORS = {
    "light tracing": {"light_tracing": True},
    "gather, the scene's r = 0.05": {"light_tracing": False},
    "gather, r = 0.1": {"light_tracing": False, "radius": 0.1},
}


def rel_rmse(got: np.ndarray, reference: np.ndarray) -> float:
    g, r = got.sum(axis=2), reference.sum(axis=2)
    return float(np.sqrt(np.mean((g - r) ** 2)) / np.mean(r))


def render(seconds: float, seed: int, settings: dict) -> np.ndarray:
    return prismatic.render("room", time=seconds, seed=seed, backend="cpu", progress=False, **SIZE, **settings)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--reference-s", type=float, default=120.0)
    args = parser.parse_args()
    t = time.perf_counter()
    reference = render(args.reference_s, 1000, ESTIMATORS["light tracing"])
    print(f"reference: light tracing, {time.perf_counter() - t:.0f} s, mean {reference.sum(axis=2).mean():.4f}")
    gathered = render(args.reference_s, 2000, ESTIMATORS["gather, r = 0.1"])
    print(f"the gather's own long render (r = 0.1, {args.reference_s:.0f} s) against it: "
          f"relRMSE {rel_rmse(gathered, reference):.4f}, mean {gathered.sum(axis=2).mean():.4f}")
    print()
    print("| estimator | " + " | ".join(f"{s:g} s" for s in TIMES) + " |")
    print("|---|" + "---|" * len(TIMES))
    for name, settings in ESTIMATORS.items():
        errors = [rel_rmse(render(s, 7 + k, settings), reference) for k, s in enumerate(TIMES)]
        print(f"| {name} | " + " | ".join(f"{e:.3f}" for e in errors) + " |")


if __name__ == "__main__":
    main()
