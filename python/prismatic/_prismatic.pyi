"""Type stubs of prismatic's compiled module (python/src/lib.rs)."""

from typing import Any, Callable, Dict, List, Optional, Tuple

import numpy as np
import numpy.typing as npt

__version__: str
# The render settings' names (the CLI's flags, spelled with underscores).
SETTINGS: List[str]

# (built-in name or path, False, None), or (TOML text, True, the file it was read from or None).
Source = Tuple[str, bool, Optional[str]]
Settings = Dict[str, Any]
Callback = Callable[[int, Optional[int]], Any]

class SceneError(ValueError):
    """A scene, setting or partial render that cannot be used."""

    file: str
    line: Optional[int]
    key: str
    reason: str

class RenderError(RuntimeError):
    """A render that failed (no adapter, a device lost, ...)."""

def render(
    source: Source,
    settings: Optional[Settings] = None,
    passes: Optional[Tuple[int, int]] = None,
    time: Optional[float] = None,
    progress: Optional[Callback] = None,
) -> npt.NDArray[np.float32]: ...
def render_partial(
    source: Source,
    passes: Tuple[int, int],
    settings: Optional[Settings] = None,
    progress: Optional[Callback] = None,
) -> bytes: ...
class Merge:
    """Partial renders merged as they come (the sums of all their passes)."""

    def __init__(self) -> None: ...
    def add(self, partial: bytes) -> None: ...
    def passes(self) -> List[Tuple[int, int]]: ...
    def image(self) -> npt.NDArray[np.float32]: ...
    def to_bytes(self) -> bytes: ...

def photons(source: Source, pass_: int = 0, settings: Optional[Settings] = None) -> Dict[str, npt.NDArray[Any]]: ...
def describe(source: Source, settings: Optional[Settings] = None) -> Dict[str, int]: ...
def scenes() -> List[str]: ...
