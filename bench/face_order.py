#!/usr/bin/env python3
"""Writes an OBJ mesh again with its faces or its vertices in a spatial order,
to measure what the order of a file costs a frame (BENCHMARKS.md, "The
dragon's face order").

    python3 bench/face_order.py faces|vertices|same IN.obj OUT.obj

- faces: the faces sorted by the Morton code of their centroid (1024 cells
  per axis), then the vertices numbered in the order the faces first use them;
- vertices: the vertices sorted by their own Morton code, the faces in the
  file's order;
- same: nothing moved.

Every mode writes the positions with the same "%f" formatting, so that the
three files hold the same values; only `v` and `f` lines are kept (texture
coordinates and file normals are dropped). Reading a face's vertex as
`i/j/k` keeps `i`; negative (relative) indices are not supported.
"""

import sys


def read(path):
    positions, faces = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                positions.append([float(t) for t in line.split()[1:4]])
            elif line.startswith("f "):
                face = [int(t.split("/")[0]) - 1 for t in line.split()[1:]]
                if any(i < 0 for i in face):
                    sys.exit(f"{path}: relative vertex indices are not supported")
                faces.append(face)
    return positions, faces


def morton(point, low, high):
    """Interleaved bits of the point's cell in a 1024³ grid over the box."""
    cells = [
        min(1023, int((point[a] - low[a]) / ((high[a] - low[a]) or 1.0) * 1024))
        for a in range(3)
    ]
    code = 0
    for bit in range(10):
        for a in range(3):
            code |= ((cells[a] >> bit) & 1) << (3 * bit + a)
    return code


def main():
    if len(sys.argv) != 4 or sys.argv[1] not in ("faces", "vertices", "same"):
        sys.exit(__doc__)
    mode, source, target = sys.argv[1:]
    positions, faces = read(source)
    low = [min(p[a] for p in positions) for a in range(3)]
    high = [max(p[a] for p in positions) for a in range(3)]
    order = list(range(len(positions)))  # new index -> old index
    if mode == "faces":

        def centroid(face):
            return [sum(positions[i][a] for i in face) / len(face) for a in range(3)]

        faces.sort(key=lambda face: morton(centroid(face), low, high))
        seen = {}
        for face in faces:
            for i in face:
                seen.setdefault(i, len(seen))
        order = sorted(seen, key=seen.get)
        order += [i for i in range(len(positions)) if i not in seen]
    elif mode == "vertices":
        order.sort(key=lambda i: morton(positions[i], low, high))
    new_index = {old: new for new, old in enumerate(order)}
    with open(target, "w") as out:
        for old in order:
            out.write("v %f %f %f\n" % tuple(positions[old]))
        for face in faces:
            out.write("f " + " ".join(str(new_index[i] + 1) for i in face) + "\n")


if __name__ == "__main__":
    main()
