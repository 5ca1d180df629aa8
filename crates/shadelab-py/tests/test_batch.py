"""shadelab.batch against `shadelab batch`: the same files, byte for byte."""

import json
import pathlib

import pytest

import shadelab
from conftest import cli_error, run_cli, uv_sphere, write_obj


def make_set(root: pathlib.Path, count: int = 6) -> pathlib.Path:
    """`count` meshes and a JSON Lines manifest of them, with one broken entry."""
    (root / "meshes").mkdir(parents=True)
    for k in range(count):
        vertices, faces = uv_sphere(8 + 4 * k)
        vertices = vertices * [1.0, 0.5 + 0.2 * k, 1.0]
        write_obj(root / "meshes" / f"m{k}.obj", vertices, faces)
    lines = [{"path": f"meshes/m{k}.obj", "id": f"m{k}"} for k in range(count)]
    lines.append({"path": "meshes/none.obj", "id": "none"})
    manifest = root / "set.jsonl"
    manifest.write_text("".join(json.dumps(line) + "\n" for line in lines))
    return manifest


def files(out: pathlib.Path) -> dict:
    return {str(p.relative_to(out)): p.read_bytes() for p in sorted(out.rglob("*.png"))}


def test_batch_writes_what_the_command_writes(cli, tmp_path):
    manifest = make_set(tmp_path)
    run_cli(cli, "batch", str(manifest), "-o", str(tmp_path / "cli"), "--views", "3",
            "--shading", "flat,phong", "--size", "64x48", "--progress", "none")
    summary = shadelab.batch(manifest, tmp_path / "py", views=3, shading=["flat", "phong"], size=(64, 48))
    assert (summary["meshes"], summary["written"], summary["failed"], summary["skipped"]) == (7, 36, 6, 0)
    assert summary["index"].name == "index.jsonl"
    assert files(tmp_path / "py") == files(tmp_path / "cli")
    assert len(files(tmp_path / "py")) == 36
    rows = [json.loads(l) for l in (tmp_path / "py" / "index.jsonl").read_text().splitlines()]
    assert sorted(r["status"] for r in rows) == ["error"] * 6 + ["ok"] * 36
    assert all("none.obj" in r["error"] for r in rows if r["status"] == "error")

    again = shadelab.batch(manifest, tmp_path / "py", views=3, shading="flat,phong", size=(64, 48))
    assert (again["written"], again["skipped"]) == (0, 36)
    with pytest.raises(RuntimeError, match="strict"):
        shadelab.batch(manifest, tmp_path / "py", views=3, shading="flat,phong", size=(64, 48), strict=True)


def test_shards_from_python_split_the_manifest(tmp_path):
    manifest = make_set(tmp_path)
    owners = {}
    for i in range(3):
        shadelab.batch(manifest, tmp_path / "out", shard=(i, 3), size=(16, 16))
        for line in (tmp_path / "out" / f"index-{i}-of-3.jsonl").read_text().splitlines():
            row = json.loads(line)
            owners.setdefault(row["id"], []).append(i)
    assert sorted(owners) == ["m0", "m1", "m2", "m3", "m4", "m5", "none"]
    assert all(len(o) == 1 for o in owners.values())


def test_batch_errors_are_the_commands(cli, tmp_path):
    missing = tmp_path / "nothing.jsonl"
    with pytest.raises(ValueError) as e:
        shadelab.batch(missing, tmp_path / "out")
    out = run_cli(cli, "batch", str(missing), "-o", str(tmp_path / "out"), check=False)
    assert out.returncode == 2
    assert str(e.value) == cli_error(out)
    manifest = make_set(tmp_path)
    with pytest.raises(ValueError, match="views"):
        shadelab.batch(manifest, tmp_path / "out", views="sphere")
    with pytest.raises(ValueError, match="shard"):
        shadelab.batch(manifest, tmp_path / "out", shard=(3, 3))
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(OSError):
        shadelab.batch(manifest, blocker / "out")
