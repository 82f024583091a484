"""What the measurement scripts read back from a render: its linear RGB
from the EXR the CLI writes, and the brightness error against a reference."""

from pathlib import Path

import Imath
import numpy as np
import OpenEXR


def read_rgb(path: Path) -> np.ndarray:
    """The R, G and B channels of an EXR, (height, width, 3)."""
    exr = OpenEXR.InputFile(str(path))
    window = exr.header()["dataWindow"]
    width, height = window.max.x - window.min.x + 1, window.max.y - window.min.y + 1
    channel = Imath.PixelType(Imath.PixelType.FLOAT)
    planes = [np.frombuffer(exr.channel(c, channel), dtype=np.float32).reshape(height, width) for c in "RGB"]
    return np.stack(planes, axis=2)


def brightness_error(got: np.ndarray, reference: np.ndarray) -> float:
    """The relRMSE of the per-pixel R + G + B: the RMSE over the reference's mean."""
    g, r = got.sum(axis=2), reference.sum(axis=2)
    return float(np.sqrt(np.mean((g - r) ** 2)) / np.mean(r))
