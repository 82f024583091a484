"""The sky both `luxcore_compare.py` and `environment_suns.py` light their
scenes with, written as a Radiance .hdr file."""

import math

import numpy as np

# The sky: an equirectangular map (prismatic's convention: row 0 at +y,
# u = 0.5 + atan2(x, -z) / 2π), white from 0.4 at the zenith to 1 at the
# horizon, black below it (what is below the floor), with a sun.
SKY_SIZE = (512, 256)
SUN_RADIUS_DEG, SUN_RADIANCE, SUN_ELEVATION_DEG = 2.5, 2000.0, 50.0
# The sun's u on the line where u and 0.75 − u meet, so that a renderer that
# reads the map mirrored sees it in the same place.
SUN_U = 0.375


def sky_texels() -> np.ndarray:
    """The sky's linear RGB, (height, width, 3)."""
    w, h = SKY_SIZE
    theta = np.pi * ((np.arange(h) + 0.5) / h)[:, None]
    phi = 2 * np.pi * ((np.arange(w) + 0.5) / w - 0.5)[None, :]
    d = np.stack([np.sin(theta) * np.sin(phi), np.cos(theta) * np.ones_like(phi), -np.sin(theta) * np.cos(phi)], -1)
    y = d[..., 1]
    radiance = np.where(y > 0, 0.4 + 0.6 * (1 - y), 0.0)
    sun_theta, sun_phi = math.radians(90 - SUN_ELEVATION_DEG), 2 * math.pi * (SUN_U - 0.5)
    sun = np.array([math.sin(sun_theta) * math.sin(sun_phi), math.cos(sun_theta),
                    -math.sin(sun_theta) * math.cos(sun_phi)])
    radiance = np.where(d @ sun > math.cos(math.radians(SUN_RADIUS_DEG)), SUN_RADIANCE, radiance)
    return np.repeat(radiance[..., None], 3, axis=2).astype(np.float32)


def write_hdr(path: str, rgb: np.ndarray) -> None:
    """A Radiance .hdr (flat RGBE scanlines) of linear `rgb`."""
    h, w, _ = rgb.shape
    peak = rgb.max(axis=2)
    lit = peak > 1e-32
    exponent = np.where(lit, np.floor(np.log2(np.where(lit, peak, 1.0))) + 1, 0)
    scale = np.where(lit, 256.0 / np.exp2(exponent), 0.0)
    mantissa = np.clip(np.floor(rgb * scale[..., None]), 0, 255).astype(np.uint8)
    e = np.where(lit, exponent + 128, 0).astype(np.uint8)
    with open(path, "wb") as f:
        f.write(f"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {h} +X {w}\n".encode())
        f.write(np.concatenate([mantissa, e[..., None]], axis=2).tobytes())
