"""A Python loop of shadelab.render over the manifest, on N threads (no PNG).

Each thread takes meshes, loads each once with trimesh and renders its views
from NumPy arrays: how a Python program that wants arrays uses the package.
"""

import argparse
import json
import pathlib
import time
from concurrent.futures import ThreadPoolExecutor

import trimesh

import shadelab


def main():
    p = argparse.ArgumentParser()
    p.add_argument("manifest")
    p.add_argument("--views", type=int, default=6)
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--threads", type=int, default=2)
    a = p.parse_args()
    base = pathlib.Path(a.manifest).parent
    paths = [base / json.loads(line)["path"] for line in open(a.manifest) if line.strip()]

    def one(path):
        mesh = trimesh.load(path, force="mesh", process=False)
        for k in range(a.views):
            shadelab.render(mesh, size=(a.size, a.size), options={"yaw": 360.0 * k / a.views})
        return a.views

    start = time.perf_counter()
    with ThreadPoolExecutor(a.threads) as pool:
        images = sum(pool.map(one, paths))
    seconds = time.perf_counter() - start
    print(json.dumps({"images": images, "seconds": seconds}))


if __name__ == "__main__":
    main()
