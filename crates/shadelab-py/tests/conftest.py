"""Shared helpers: the `shadelab` command to compare against, and small meshes."""

import os
import pathlib
import subprocess

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[3]


@pytest.fixture(scope="session")
def cli() -> str:
    """The `shadelab` binary (SHADELAB_BIN, else target/release/shadelab)."""
    path = os.environ.get("SHADELAB_BIN", str(REPO / "target" / "release" / "shadelab"))
    assert os.access(path, os.X_OK), f"{path}: build it with `cargo build --release` first"
    return path


def run_cli(cli: str, *args: str, cwd=None, check=True) -> subprocess.CompletedProcess:
    out = subprocess.run([cli, *args], cwd=cwd, capture_output=True, text=True)
    if check:
        assert out.returncode == 0, out.stderr
    return out


def cli_error(out: subprocess.CompletedProcess) -> str:
    """The message the command printed after `error: `."""
    lines = [l for l in out.stderr.splitlines() if l.startswith("error: ")]
    assert lines, out.stderr
    return lines[-1][len("error: "):]


def uv_sphere(slices: int = 24):
    """A UV sphere: vertices (N, 3) float64 and triangles (M, 3) int64."""
    stacks = slices // 2
    theta = np.pi * np.arange(stacks + 1) / stacks
    phi = 2 * np.pi * np.arange(slices) / slices
    t, p = np.meshgrid(theta, phi, indexing="ij")
    vertices = np.stack([np.sin(t) * np.cos(p), np.cos(t), np.sin(t) * np.sin(p)], axis=-1).reshape(-1, 3)
    faces = []
    for i in range(stacks):
        for j in range(slices):
            a, b = i * slices + j, (i + 1) * slices + j
            c, d = (i + 1) * slices + (j + 1) % slices, i * slices + (j + 1) % slices
            faces += [(a, d, c), (a, c, b)]
    return vertices, np.array(faces, dtype=np.int64)


def write_obj(path: pathlib.Path, vertices, faces) -> None:
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in np.asarray(vertices, dtype=np.float32).tolist()]
    lines += ["f " + " ".join(str(int(k) + 1) for k in face) for face in faces]
    path.write_text("\n".join(lines) + "\n")
