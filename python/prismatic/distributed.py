"""Renders spread over a Dask cluster, merged exactly.

::

    import prismatic.distributed
    image = prismatic.distributed.render("sphere", passes=64, chunk=4)             # a local cluster
    image = prismatic.distributed.render("sphere", passes=64, address="tcp://head:8786")

The passes are cut into ranges of ``chunk``; each range is one task that
renders a partial render (the exact integer sums of its passes) on a worker;
the partials are merged as they come back. Pass ``k``'s photons depend only
on the scene and ``k``, so the result is bit for bit the image of
``prismatic.render(scene, passes=N)`` on one machine, whatever the number of
workers, the order the tasks finish in, or a worker that dies: its tasks
run again elsewhere and give the same bits.

The scene travels once per worker (scattered with ``broadcast=True``), not
once per task: a built-in scene by name, a TOML file as its text. A glTF
file and the mesh files a TOML scene names are read by the workers at the
same path (a shared file system).
"""

from __future__ import annotations

import os
import uuid
from typing import Any, List, Optional, Tuple

import numpy as np

from . import Progress, Scene, _describe, _prismatic, _progress, _scene, _settings

__all__ = ["render", "ranges"]


def ranges(passes: int, chunk: int) -> List[Tuple[int, int]]:
    """Passes ``0..passes`` cut into ranges of ``chunk`` (the last may be shorter)."""
    if passes < 1:
        raise ValueError(f"passes must be at least 1, got {passes}")
    if chunk < 1:
        raise ValueError(f"chunk must be at least 1, got {chunk}")
    return [(a, min(a + chunk, passes)) for a in range(0, passes, chunk)]


def _source(scene: Scene) -> Tuple[str, bool, Optional[str]]:
    """What the workers get: a TOML file's text (read here, once; mesh files
    it names are read by the workers at their absolute paths), anything else
    as named."""
    source = _scene(scene)
    path = source[0]
    if not source[1] and os.path.isfile(path) and not path.lower().endswith((".gltf", ".glb")):
        with open(path, encoding="utf-8") as f:
            return f.read(), True, os.path.abspath(path)
    return source


def _render_range(source: Tuple[str, bool, Optional[str]], passes: Tuple[int, int], settings: dict) -> bytes:
    """A task: passes ``passes`` of the scene into a partial render's bytes."""
    return _prismatic.render_partial(source, passes, settings, None)


def _local_cluster(workers: Optional[int]) -> Any:
    """A cluster of worker processes on this machine, one rendering thread each."""
    from dask.distributed import LocalCluster

    n = workers or os.cpu_count() or 1
    return LocalCluster(
        n_workers=n,
        threads_per_worker=1,
        processes=True,
        dashboard_address=None,
        env={"RAYON_NUM_THREADS": "1"},
    )


def render(
    scene: Scene,
    passes: Optional[int] = None,
    chunk: int = 2,
    address: Optional[str] = None,
    *,
    workers: Optional[int] = None,
    progress: Progress = True,
    client: Any = None,
    **settings: Any,
) -> np.ndarray:
    """Renders ``scene``'s passes ``0..passes`` (default: the scene's) in
    ranges of ``chunk`` on a Dask cluster and returns the image: float32,
    (height, width, 3), linear RGB, bit for bit ``prismatic.render``'s.

    ``address``: a running scheduler (``tcp://host:8786``); ``None`` starts a
    local cluster of ``workers`` processes (default: one per core) for this
    call. ``client``: an existing ``dask.distributed.Client`` instead.
    ``progress``: a callable ``(passes_done, passes)`` called as ranges
    complete, ``True`` for a tqdm bar, ``False`` for nothing. Other keywords:
    the CLI's settings (``photons``, ``width``, ``backend``, …).
    """
    from dask.distributed import Client, as_completed

    settings = _settings(settings)
    # Checked here, so that a bad scene or setting raises before any task runs.
    described = _describe(scene, **settings)
    total = described["passes"] if passes is None else int(passes)
    parts = ranges(total, chunk)
    callback, close = _progress(progress, "distributed render")

    cluster = None
    own_client = client is None
    if own_client:
        if address is None:
            cluster = _local_cluster(workers)
            client = Client(cluster)
        else:
            client = Client(address)
    try:
        # One object (a list's element), not a tuple's three: Dask would
        # scatter those one by one. Keys are this call's own (hash=False, a
        # random tag): a key reused from a call whose data is being released
        # can be lost on the scheduler.
        [source] = client.scatter([_source(scene)], broadcast=True, hash=False)
        tag = f"prismatic-{described['fingerprint']:016x}-{uuid.uuid4().hex[:8]}"
        futures = [
            client.submit(_render_range, source, (a, b), settings, key=f"{tag}-{a}-{b}", pure=False)
            for a, b in parts
        ]
        merged = _prismatic.Merge()
        for future in as_completed(futures):
            merged.add(future.result())
            future.release()
            if callback is not None:
                callback(sum(b - a for a, b in merged.passes()), total)
        return merged.image()
    finally:
        close()
        if own_client:
            client.close()
        if cluster is not None:
            cluster.close()

