"""prismatic: N-band dispersion photon mapping from Python.

Render a scene into a numpy array::

    import prismatic
    image = prismatic.render("sphere", passes=8, photons=65_000)   # (400, 400, 3) float32, linear RGB

``scene`` is a built-in scene's name (``prismatic.scenes()``), a path to a
scene file (TOML, ``.gltf``, ``.glb``) or the TOML text of a scene. The
settings are the ``prismatic render`` command's flags by name: ``width``,
``height``, ``photons``, ``bands`` (``"paper3"``, ``"paper7"`` or a
number), ``radius``, ``radius_mode``, ``seed``, ``estimator``,
``light_tracing`` (``True`` or ``False``), ``wavelengths``, ``photon_sequence``
(``"sobol"`` or ``"random"``), ``view_paths`` (``"centre"``, ``"hero"`` or ``"sampled"``), ``white_point`` (``"E"`` or ``"D65"``),
``tone_map`` and ``auto_exposure`` (which change only a PNG the CLI writes, not
the linear image returned here), ``backend`` (``"auto"``, ``"cpu"``, ``"gpu"``,
``"reference"``), and for renders ``passes`` and ``time``. The result is
exactly the image ``prismatic render ... -o FILE.exr`` writes for the same
scene and settings.

Renders run with the GIL released. Progress goes to ``progress``: a callable
``(done, total)`` per pass, ``True`` for a tqdm bar (when tqdm is
installed), ``False`` or ``None`` for nothing. A scene, setting or partial
render that cannot be used raises :class:`SceneError` with the CLI's message
(``file``, ``line``, ``key`` and ``reason`` as attributes); a render that
fails raises :class:`RenderError`.

Renders spread over a Dask cluster: :mod:`prismatic.distributed`.
"""

from __future__ import annotations

import os
from typing import Any, Callable, Dict, Iterable, List, Optional, Tuple, Union

import numpy as np

from . import _prismatic
from ._prismatic import RenderError, SceneError, __version__

__all__ = [
    "render",
    "render_partial",
    "merge",
    "photons",
    "scenes",
    "SceneError",
    "RenderError",
    "__version__",
]

Scene = Union[str, "os.PathLike[str]"]
Progress = Union[None, bool, Callable[[int, Optional[int]], Any]]

# The settings every call takes: the CLI's flags by name (one list, in the
# renderer: prismatic_cli::settings), and the backend.
SETTINGS = tuple(_prismatic.SETTINGS) + ("backend",)


def scenes() -> List[str]:
    """The built-in scenes' names."""
    return list(_prismatic.scenes())


def _scene(scene: Scene) -> Tuple[str, bool, Optional[str]]:
    """The scene as the module takes it: (built-in name or path, False, None),
    or (TOML text, True, None) for a string with a line break."""
    if isinstance(scene, os.PathLike):
        return os.fspath(scene), False, None
    if not isinstance(scene, str):
        raise TypeError(f"scene must be a built-in name, a path or TOML text, not {type(scene).__name__}")
    return scene, "\n" in scene, None


def _settings(settings: Dict[str, Any]) -> Dict[str, Any]:
    """The keyword settings, checked by name (values are checked by the renderer)."""
    unknown = sorted(set(settings) - set(SETTINGS))
    if unknown:
        raise TypeError(f"unknown setting(s) {', '.join(unknown)}; the settings are: {', '.join(SETTINGS)}")
    return {k: v for k, v in settings.items() if v is not None}


class _Bar:
    """A tqdm bar over passes, as a progress callable."""

    def __init__(self, description: str) -> None:
        from tqdm.auto import tqdm

        self._bar = tqdm(desc=description, unit="pass")

    def __call__(self, done: int, total: Optional[int]) -> None:
        if total is not None and self._bar.total != total:
            self._bar.total = total
        self._bar.update(done - self._bar.n)

    def close(self) -> None:
        self._bar.close()


def _progress(progress: Progress, description: str) -> Tuple[Optional[Callable[[int, Optional[int]], Any]], Callable[[], None]]:
    """(callable or None, close) for a progress argument."""
    if progress is True:
        try:
            bar = _Bar(description)
        except ImportError:
            return None, lambda: None
        return bar, bar.close
    if progress is None or progress is False:
        return None, lambda: None
    if not callable(progress):
        raise TypeError("progress must be a callable (done, total), True for a tqdm bar, or False")
    return progress, lambda: None


def _passes(passes: Union[None, int, range, Tuple[int, int]]) -> Optional[Tuple[int, int]]:
    if passes is None:
        return None
    if isinstance(passes, range):
        if passes.step != 1:
            raise ValueError("passes must be a range with step 1")
        return passes.start, passes.stop
    if isinstance(passes, tuple):
        start, stop = passes
        return int(start), int(stop)
    return 0, int(passes)


def render(
    scene: Scene,
    *,
    passes: Union[None, int, range, Tuple[int, int]] = None,
    time: Optional[float] = None,
    progress: Progress = True,
    **settings: Any,
) -> np.ndarray:
    """Renders ``scene`` and returns its image: float32, (height, width, 3), linear RGB.

    ``passes``: N (passes 0..N), a ``range`` or ``(start, stop)``; default the
    scene's, or with ``time`` as many as fit. ``time``: stop after the pass
    that crosses this many seconds. Other keywords: the CLI's settings and
    environment flags by name (``photons=``, ``environment="studio"``).
    """
    source = _scene(scene)
    callback, close = _progress(progress, "render")
    try:
        return _prismatic.render(source, _settings(settings), _passes(passes), time, callback)
    finally:
        close()


def render_partial(
    scene: Scene,
    passes: Union[int, range, Tuple[int, int]],
    *,
    progress: Progress = False,
    **settings: Any,
) -> bytes:
    """Renders passes ``passes`` of ``scene`` into a partial render: the
    bytes ``prismatic render --passes A..B --partial FILE`` writes, for
    :func:`merge` (or ``prismatic merge``)."""
    source = _scene(scene)
    callback, close = _progress(progress, "render")
    try:
        return _prismatic.render_partial(source, _passes(passes), _settings(settings), callback)
    finally:
        close()


def merge(partials: Iterable[bytes]) -> np.ndarray:
    """Merges partial renders into the image one render of all their passes
    gives, bit for bit (float32, (height, width, 3), linear RGB). Partials of
    different scenes, settings, sizes or backends, and overlapping passes,
    raise :class:`SceneError`."""
    merged = _prismatic.Merge()
    for partial in partials:
        merged.add(partial)
    return merged.image()


def photons(scene: Scene, *, pass_: int = 0, **settings: Any) -> Dict[str, np.ndarray]:
    """The caustic photons of pass ``pass_`` as columns, the CSV that
    ``prismatic photons`` writes: ``emission`` (uint32), ``band`` (int32, -1
    for white photons), ``lambda_nm`` (float32, the wavelength the photon
    was traced at; NaN for white photons),
    ``x``, ``y``, ``z`` (float64, world coordinates), ``dir_x``, ``dir_y``,
    ``dir_z`` and ``power`` (float32), in canonical order."""
    return dict(_prismatic.photons(_scene(scene), pass_, _settings(settings)))


def _describe(scene: Scene, **settings: Any) -> Dict[str, int]:
    """The scene's fingerprint, size, passes and photons after the settings."""
    return dict(_prismatic.describe(_scene(scene), _settings(settings)))
