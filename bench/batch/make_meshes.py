"""Makes the benchmark's meshes: decimated copies of ../shared/models at several sizes.

    python bench/batch/make_meshes.py MODELS_DIR WORK_DIR [COUNT]

Writes WORK_DIR/meshes/<model>-<faces>.obj and WORK_DIR/manifest.jsonl (COUNT
meshes, default 200: the seven models, each at a geometric series of triangle
counts from 300 to its full size, quadric decimation by fast-simplification).
Nothing here is committed: the meshes are made afresh in a work folder.
"""

import json
import pathlib
import sys

import fast_simplification
import numpy as np
import trimesh


def main() -> None:
    models, work = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    count = int(sys.argv[3]) if len(sys.argv) > 3 else 200
    (work / "meshes").mkdir(parents=True, exist_ok=True)
    sources = sorted(models.glob("*.obj"))
    assert sources, f"no .obj files in {models}"
    per_model = -(-count // len(sources))
    entries = []
    for source in sources:
        mesh = trimesh.load(source, force="mesh", process=False)
        vertices = np.asarray(mesh.vertices, dtype=np.float32)
        faces = np.asarray(mesh.faces, dtype=np.int64)
        full = len(faces)
        targets = np.unique(np.geomspace(min(300, full), full, per_model).astype(int))
        # Duplicated counts (small models) become distinct meshes by index.
        while len(targets) < per_model:
            targets = np.append(targets, targets[-1])
        for k, target in enumerate(targets[:per_model]):
            if target >= full:
                v, f = vertices, faces
            else:
                v, f = fast_simplification.simplify(vertices, faces, target_reduction=1 - target / full)
            name = f"{source.stem}-{k:02d}-{len(f)}"
            path = work / "meshes" / f"{name}.obj"
            if not path.exists():
                trimesh.Trimesh(v, f, process=False).export(path)
            entries.append({"path": f"meshes/{name}.obj", "id": name, "triangles": int(len(f))})
    entries = entries[:count]
    with open(work / "manifest.jsonl", "w") as out:
        for e in entries:
            out.write(json.dumps({"path": e["path"], "id": e["id"]}) + "\n")
    total = sum(e["triangles"] for e in entries)
    print(f"{len(entries)} meshes, {total} triangles in all, "
          f"{min(e['triangles'] for e in entries)}..{max(e['triangles'] for e in entries)} each",
          file=sys.stderr)


if __name__ == "__main__":
    main()
