"""shadelab: flat, Gouraud and Phong shading on an exact CPU rasterizer.

Render a mesh into a NumPy array::

    import shadelab
    img = shadelab.render("bunny.obj", shading="phong", size=(512, 512))
    img.shape, img.dtype          # (512, 512, 3), uint8

or render a whole manifest of meshes into PNGs, as ``shadelab batch`` does::

    shadelab.batch("meshes.jsonl", "out/", views=6, shading="all")

Settings are the scene file's keys (see the project's README): keyword
arguments set them over an optional ``scene`` file, exactly as the command
line's flags do, so an image equals the one ``shadelab render`` writes for the
same settings. Rendering releases the GIL, so threads render in parallel.
Errors are ``ValueError`` (bad input) or ``OSError`` (a file that cannot be
read or written), with the messages the command prints.
"""

from __future__ import annotations

import json
import os
from typing import Any, Dict, Iterable, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _shadelab

__all__ = ["render", "batch", "read_png", "BUILTIN_MODELS", "SHADINGS"]

#: Names of the built-in models (``"teapot"``, ``"sphere"``, …).
BUILTIN_MODELS: Tuple[str, ...] = tuple(_shadelab.BUILTIN_MODELS)
#: The three shading methods.
SHADINGS: Tuple[str, ...] = ("flat", "gouraud", "phong")

_DEFAULT_SIZE = (512, 512)


def _settings(
    *,
    shading: Optional[str],
    size: Optional[Tuple[int, int]],
    camera: Optional[Mapping[str, Any]],
    lights: Optional[Sequence[Mapping[str, Any]]],
    material: Optional[Mapping[str, Any]],
    ambient: Optional[Mapping[str, Any]],
    model: Optional[Mapping[str, Any]],
    options: Optional[Mapping[str, Any]],
    scene_given: bool,
) -> str:
    """The keyword arguments as scene-file sections, in JSON."""
    out: Dict[str, Any] = {}
    render: Dict[str, Any] = dict(options or {})
    if shading is not None:
        render["shading"] = shading
    if size is None and not scene_given:
        size = _DEFAULT_SIZE
    if size is not None:
        try:
            width, height = size
        except (TypeError, ValueError):
            raise ValueError(f"size must be (width, height), got {size!r}") from None
        render["width"], render["height"] = int(width), int(height)
    if render:
        out["render"] = render
    if camera is not None:
        out["camera"] = dict(camera)
    if lights is not None:
        out["lights"] = [dict(light) for light in lights]
    if material is not None:
        out["material"] = dict(material)
    if ambient is not None:
        out["ambient"] = dict(ambient)
    if model is not None:
        out["model"] = dict(model)
    return json.dumps(_plain(out))


def _plain(value: Any) -> Any:
    """``value`` with NumPy scalars and arrays made plain Python, ``None`` keys dropped."""
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items() if v is not None}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    return value


def _fspath(path: Union[str, os.PathLike, None]) -> Optional[str]:
    return None if path is None else os.fspath(path)


MeshLike = Union[str, os.PathLike, Tuple[Any, Any], Any]


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
    scene: Union[str, os.PathLike, None] = None,
    alpha: bool = False,
) -> np.ndarray:
    """Render one image of a mesh and return it as a NumPy array.

    Args:
        mesh: a built-in model's name (``"teapot"``), a mesh file's path
            (``.obj``, ``.stl``, ``.ply``, ``.gltf``, ``.glb``), a pair
            ``(vertices, faces)`` of arrays — vertices ``(N, 3)`` floats, faces
            ``(M, K)`` vertex indices, ``K >= 3`` — or any object with
            ``.vertices`` and ``.faces`` (a ``trimesh.Trimesh``). ``None``: the
            scene file's model.
        shading: ``"flat"``, ``"gouraud"`` or ``"phong"``.
        size: ``(width, height)`` in pixels; default the scene file's size,
            or 512×512 without a scene file.
        camera: the ``[camera]`` section: ``eye``, ``target``, ``up``,
            ``fov_y``, ``near``, ``far``. Without it the camera frames the model.
        lights: the ``[[lights]]``: dicts with ``kind`` (``"point"`` or
            ``"directional"``), ``position`` or ``direction``, ``color``,
            ``intensity``.
        material: the ``[material]`` keys: ``ka``, ``kd``, ``ks`` (RGB 0–255)
            and ``shininess``.
        ambient: the ``[ambient]`` keys: ``color``, ``intensity``.
        model: the ``[model]`` keys: ``normals``, ``crease_angle``, ``detail``.
        options: further ``[render]`` keys (``background``, ``yaw``,
            ``pitch``, ``zoom``, ``cull_backfaces``, ``specular``, …).
        scene: a scene file (TOML) whose values the arguments override.
        alpha: add a fourth channel, 255 where the model covers the pixel.

    Returns:
        ``uint8`` array of shape ``(height, width, 3)``, or ``(…, 4)`` with ``alpha``.

    Raises:
        ValueError: invalid settings or mesh, with the command's message.
        OSError: a file that cannot be read.
    """
    settings = _settings(
        shading=shading,
        size=size,
        camera=camera,
        lights=lights,
        material=material,
        ambient=ambient,
        model=model,
        options=options,
        scene_given=scene is not None,
    )
    scene_path = _fspath(scene)
    if mesh is None or isinstance(mesh, (str, os.PathLike)):
        return _shadelab.render_source(scene_path, settings, _fspath(mesh), alpha)
    if hasattr(mesh, "vertices") and hasattr(mesh, "faces"):
        vertices, faces = mesh.vertices, mesh.faces
    else:
        try:
            vertices, faces = mesh
        except (TypeError, ValueError):
            raise ValueError(
                "mesh must be a path, a built-in model's name, (vertices, faces), "
                f"or an object with .vertices and .faces; got {type(mesh).__name__}"
            ) from None
    vertices = np.ascontiguousarray(vertices, dtype=np.float32)
    faces = np.asarray(faces)
    if faces.dtype.kind not in "iu":
        raise ValueError(f"faces must hold integer vertex indices, got dtype {faces.dtype}")
    faces = np.ascontiguousarray(faces, dtype=np.int64)
    if vertices.ndim != 2 or faces.ndim != 2:
        raise ValueError(
            f"vertices must be (N, 3) and faces (M, K); got shapes {vertices.shape} and {faces.shape}"
        )
    return _shadelab.render_arrays(vertices, faces, scene_path, settings, alpha)


def batch(
    manifest: Union[str, os.PathLike],
    output: Union[str, os.PathLike],
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
    scene: Union[str, os.PathLike, None] = None,
    root: Union[str, os.PathLike, None] = None,
    jobs: int = 0,
    frame_threads: int = 1,
    max_mesh_bytes: Optional[int] = None,
    png: str = "fast",
    progress: bool = False,
) -> Dict[str, Any]:
    """Render every mesh of a manifest into PNGs, as ``shadelab batch`` does.

    The manifest is JSON Lines (``{"path": ..., "id": ...}`` per line, with
    optional ``views``, ``size`` and ``shading``) or CSV with a ``path[,id]``
    header; paths are relative to it. Outputs are
    ``output/<id>/<view>_<mode>.png``, with one row per output in
    ``output/index.jsonl`` (``index-I-of-N.jsonl`` for a shard). Outputs that
    already exist are skipped unless ``force``; a broken mesh becomes error
    rows and the run goes on.

    Args:
        manifest: the manifest file.
        output: the output folder (made if missing).
        views: a number of views on a ring about the up axis, or ``"cube"``.
        shading: one method, ``"all"``, or a list; default the scene's (Phong).
        shard: ``(I, N)`` or ``"I/N"``: this share of the manifest, by a stable
            hash of each id.
        force: draw outputs again even when they exist.
        strict: raise ``RuntimeError`` when any mesh or line failed.
        size, camera, lights, material, ambient, model, options, scene:
            the shared settings, as in :func:`render` (size defaults to the
            scene's, else 800×600 as on the command line).
        root: mesh paths must stay inside this folder (default: the manifest's).
        jobs: meshes drawn at once (0: two per core).
        frame_threads: threads drawing each mesh's frames.
        max_mesh_bytes: larger mesh files are error rows.
        png: ``"fast"`` or ``"small"`` compression.
        progress: show progress on standard error.

    Returns:
        The summary: ``meshes``, ``meshes_failed``, ``written``, ``skipped``,
        ``failed``, ``bad_lines``, ``seconds``, ``index`` and ``text``.

    Raises:
        ValueError: invalid settings or manifest.
        OSError: the output folder or index cannot be written.
        RuntimeError: with ``strict``, when anything failed.
    """
    settings = _settings(
        shading=None,
        size=size,
        camera=camera,
        lights=lights,
        material=material,
        ambient=ambient,
        model=model,
        options=options,
        scene_given=True,
    )
    if shading is not None and not isinstance(shading, str):
        shading = ",".join(shading)
    if shard is not None and not isinstance(shard, str):
        index, count = shard
        shard = f"{int(index)}/{int(count)}"
    summary = _shadelab.batch(
        os.fspath(manifest),
        os.fspath(output),
        _fspath(scene),
        settings,
        str(views),
        shading,
        shard,
        force,
        _fspath(root),
        int(jobs),
        int(frame_threads),
        max_mesh_bytes,
        png,
        progress,
    )
    if strict and (summary["failed"] or summary["bad_lines"]):
        raise RuntimeError(
            f"{summary['failed']} images and {summary['bad_lines']} manifest lines failed "
            f"(strict); see {summary['index']}"
        )
    return summary


def read_png(path: Union[str, os.PathLike]) -> np.ndarray:
    """Read an 8-bit RGB or RGBA PNG into a ``uint8`` array ``(height, width, 3)``."""
    return _shadelab.read_png(os.fspath(path))
