#!/usr/bin/env python3
"""Computes core/data/reflectance_primaries.csv: the three reflectance
spectra whose mix r·R(λ) + g·G(λ) + b·B(λ) is the reflectance of the linear
RGB albedo (r, g, b) (Mallett & Yuksel, "Spectral Primary Decomposition for
Rendering with sRGB Reflectance", EGSR 2019), for prismatic's colour space:
linear sRGB of CIE 1931 with the equal-energy light white (the renderer's
`WavelengthRgb`).

The primaries are the smoothest (least sum of squared differences between
neighbouring 5 nm samples) that
- lie in [0, 1] (every albedo in the unit cube is a valid reflectance),
- sum to 1 at every wavelength (white (1, 1, 1) is exactly flat, grey g is
  exactly the flat g),
- have colours (1, 0, 0), (0, 1, 0) and (0, 0, 1) under the equal-energy
  light, with the renderer's colour of a wavelength and both spectra linear
  between the 5 nm rows (so RGB → reflectance → RGB is exact).

A convex quadratic programme, solved here by ADMM (numpy only). Run:
    target/python/bin/python scripts/reflectance_primaries.py > core/data/reflectance_primaries.csv
"""

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
XYZ_TO_SRGB = np.array([[3.2404542, -1.5371385, -0.4985314],
                        [-0.9692660, 1.8760108, 0.0415560],
                        [0.0556434, -0.2040259, 1.0572252]])
LO, HI, STEP = 380, 780, 5


def colours() -> np.ndarray:
    """Linear RGB of unit flux at 380, 385, ..., 780 nm, white for E."""
    rows = np.loadtxt(ROOT / "core/data/cie1931_2deg_5nm.csv", delimiter=",", skiprows=2)
    keep = (rows[:, 0] >= LO) & (rows[:, 0] <= HI)
    rgb = rows[keep, 1:] @ XYZ_TO_SRGB.T
    # The exact integral of the piecewise-linear table over the range.
    integral = (rgb[:-1] + rgb[1:]).sum(axis=0) * STEP / 2
    return rgb / (integral / (HI - LO))


def colour_rows(rgb: np.ndarray) -> np.ndarray:
    """Matrix C (3 × n): C @ s is the colour under E of the spectrum s, both
    linear between the samples (the exact integral of their product)."""
    n = len(rgb)
    c = np.zeros((3, n))
    for i in range(n - 1):
        a0, a1 = rgb[i], rgb[i + 1]
        c[:, i] += (2 * a0 + a1) * STEP / 6
        c[:, i + 1] += (a0 + 2 * a1) * STEP / 6
    return c / (HI - LO)


def solve(rgb: np.ndarray, rho: float = 1.0, iterations: int = 20000) -> np.ndarray:
    n = len(rgb)
    c = colour_rows(rgb)
    # Variables x = (R, G, B), 3n of them.
    d = np.diff(np.eye(n), axis=0)
    q = np.kron(np.eye(3), d.T @ d)
    # Equalities: the three sum to 1 at each sample; R and G have their
    # colours (B's follow from these, since C @ 1 = (1, 1, 1)).
    a = [np.hstack([np.eye(n)] * 3)]
    b = [np.ones(n)]
    for p in range(2):
        for k in range(3):
            row = np.zeros(3 * n)
            row[p * n:(p + 1) * n] = c[k]
            a.append(row[None, :])
            b.append(np.array([1.0 if k == p else 0.0]))
    a, b = np.vstack(a), np.concatenate(b)
    m = len(b)
    kkt = np.block([[q + rho * np.eye(3 * n), a.T], [a, np.zeros((m, m))]])
    kkt_inv = np.linalg.inv(kkt)
    z = np.full(3 * n, 1 / 3)
    u = np.zeros(3 * n)
    for _ in range(iterations):
        x = (kkt_inv @ np.concatenate([rho * (z - u), b]))[:3 * n]
        z_old = z
        z = np.clip(x + u, 0.0, 1.0)
        u += x - z
        if np.abs(x - z).max() < 1e-12 and np.abs(z - z_old).max() < 1e-12:
            break
    return z.reshape(3, n)


def main() -> None:
    rgb = colours()
    p = solve(rgb)
    c = colour_rows(rgb)
    print(f"colours of the primaries (rows):\n{p @ c.T}", file=sys.stderr)
    print(f"sum range: {p.sum(axis=0).min():.9f}..{p.sum(axis=0).max():.9f}, "
          f"value range {p.min():.3g}..{p.max():.6f}", file=sys.stderr)
    print("# Reflectance primaries (Mallett & Yuksel 2019) for linear sRGB with the equal-energy white; "
          "scripts/reflectance_primaries.py")
    print("lambda_nm,red,green,blue")
    for i, nm in enumerate(range(LO, HI + 1, STEP)):
        print(f"{nm},{p[0, i]:.9f},{p[1, i]:.9f},{p[2, i]:.9f}")


if __name__ == "__main__":
    main()
