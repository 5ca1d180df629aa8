"""Type stubs for shadelab (see the module's docstrings)."""

import os
from typing import Any, Dict, Iterable, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

BUILTIN_MODELS: Tuple[str, ...]
SHADINGS: Tuple[str, ...]

MeshLike = Union[str, os.PathLike[str], Tuple[npt.ArrayLike, npt.ArrayLike], Any, None]

def render(
    mesh: MeshLike = None,
    shading: Optional[str] = "phong",
    size: Optional[Tuple[int, int]] = None,
    camera: Optional[Mapping[str, Any]] = None,
    lights: Optional[Sequence[Mapping[str, Any]]] = None,
    material: Optional[Mapping[str, Any]] = None,
    *,
    ambient: Optional[Mapping[str, Any]] = None,
    model: Optional[Mapping[str, Any]] = None,
    options: Optional[Mapping[str, Any]] = None,
    scene: Union[str, os.PathLike[str], None] = None,
    alpha: bool = False,
) -> npt.NDArray[np.uint8]:
    """Render one image of a mesh; ``uint8`` array ``(height, width, 3 or 4)``."""
    ...

def batch(
    manifest: Union[str, os.PathLike[str]],
    output: Union[str, os.PathLike[str]],
    *,
    views: Union[int, str] = 1,
    shading: Union[str, Iterable[str], None] = None,
    shard: Union[Tuple[int, int], str, None] = None,
    force: bool = False,
    strict: bool = False,
    size: Optional[Tuple[int, int]] = None,
    camera: Optional[Mapping[str, Any]] = None,
    lights: Optional[Sequence[Mapping[str, Any]]] = None,
    material: Optional[Mapping[str, Any]] = None,
    ambient: Optional[Mapping[str, Any]] = None,
    model: Optional[Mapping[str, Any]] = None,
    options: Optional[Mapping[str, Any]] = None,
    scene: Union[str, os.PathLike[str], None] = None,
    root: Union[str, os.PathLike[str], None] = None,
    jobs: int = 0,
    frame_threads: int = 1,
    max_mesh_bytes: Optional[int] = None,
    png: str = "fast",
    progress: bool = False,
) -> Dict[str, Any]:
    """Render every mesh of a manifest into PNGs, as ``shadelab batch`` does."""
    ...

def read_png(path: Union[str, os.PathLike[str]]) -> npt.NDArray[np.uint8]:
    """Read an 8-bit PNG into a ``uint8`` array ``(height, width, 3)``."""
    ...
