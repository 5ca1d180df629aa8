"""pyrender (EGL) or Open3D's offscreen renderer on the benchmark's manifest.

    python bench/batch/others.py pyrender|open3d MANIFEST [--views 6] [--size 512]

Renders every mesh of the manifest from the same cameras as
`shadelab batch --views N` (the mesh centred on its bounding box and scaled
to a unit bounding sphere, a 45° camera at shadelab's framing distance on
+z, turned 360°·k/N about +y; one point light at (2, 2, 3)), and prints one
JSON line: renderer, GL_RENDERER, images, seconds, images per second.
A frame is the mesh's share of loading plus render and read-back into a
NumPy array; no PNG is written (shadelab's numbers include PNG encoding).
"""

import argparse
import json
import math
import os
import pathlib
import sys
import time

import numpy as np
import trimesh


def cameras(views: int, aspect: float = 1.0):
    half_y = math.radians(45.0) / 2
    half_x = math.atan(math.tan(half_y) * aspect)
    distance = 1.05 / math.sin(min(half_y, half_x))
    for k in range(views):
        yaw = 2 * math.pi * k / views
        yield np.array([distance * math.sin(yaw), 0.0, distance * math.cos(yaw)]), distance


def look_at(eye):
    forward = -eye / np.linalg.norm(eye)
    right = np.cross(forward, [0.0, 1.0, 0.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    pose = np.eye(4)
    pose[:3, 0], pose[:3, 1], pose[:3, 2], pose[:3, 3] = right, up, -forward, eye
    return pose


def load(path):
    mesh = trimesh.load(path, force="mesh", process=False)
    v = np.asarray(mesh.vertices, dtype=np.float64)
    lo, hi = v.min(axis=0), v.max(axis=0)
    centre = (lo + hi) / 2
    radius = np.linalg.norm(v - centre, axis=1).max()
    mesh.vertices = (v - centre) / (radius if radius > 0 else 1.0)
    return mesh


def run_pyrender(paths, views, size):
    os.environ.setdefault("PYOPENGL_PLATFORM", "egl")
    import pyrender
    from OpenGL import GL

    renderer = pyrender.OffscreenRenderer(size, size)
    material = pyrender.MetallicRoughnessMaterial(baseColorFactor=[1.0, 0.235, 0.235, 1.0], metallicFactor=0.0,
                                                  roughnessFactor=0.5)
    images = 0
    start = time.perf_counter()
    for path in paths:
        mesh = load(path)
        scene = pyrender.Scene(bg_color=[0, 0, 0, 1], ambient_light=[0.2, 0.2, 0.2])
        scene.add(pyrender.Mesh.from_trimesh(mesh, material=material, smooth=True))
        light = np.eye(4)
        light[:3, 3] = [2, 2, 3]
        scene.add(pyrender.PointLight(intensity=30.0), pose=light)
        camera = None
        for eye, distance in cameras(views):
            cam = pyrender.PerspectiveCamera(yfov=math.radians(45), znear=max(distance - 2, 0.01 * distance),
                                             zfar=distance + 2)
            if camera is not None:
                scene.remove_node(camera)
            camera = scene.add(cam, pose=look_at(eye))
            color, _ = renderer.render(scene)
            images += 1
    seconds = time.perf_counter() - start
    gl = GL.glGetString(GL.GL_RENDERER).decode() + " | " + GL.glGetString(GL.GL_VERSION).decode()
    renderer.delete()
    return images, seconds, gl, color


def run_open3d(paths, views, size):
    import open3d as o3d

    renderer = o3d.visualization.rendering.OffscreenRenderer(size, size)
    material = o3d.visualization.rendering.MaterialRecord()
    material.shader = "defaultLit"
    material.base_color = [1.0, 0.235, 0.235, 1.0]
    renderer.scene.set_background([0, 0, 0, 1])
    images = 0
    start = time.perf_counter()
    for path in paths:
        mesh = load(path)
        o3 = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(mesh.vertices),
                                       o3d.utility.Vector3iVector(np.asarray(mesh.faces, dtype=np.int32)))
        o3.compute_vertex_normals()
        renderer.scene.clear_geometry()
        renderer.scene.add_geometry("mesh", o3, material)
        for eye, distance in cameras(views):
            renderer.setup_camera(45.0, [0, 0, 0], eye.tolist(), [0, 1, 0])
            color = np.asarray(renderer.render_to_image())
            images += 1
    seconds = time.perf_counter() - start
    return images, seconds, "Open3D (Filament)", color


def main():
    p = argparse.ArgumentParser()
    p.add_argument("renderer", choices=["pyrender", "open3d"])
    p.add_argument("manifest")
    p.add_argument("--views", type=int, default=6)
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--image", help="save the last image here (PNG), to look at")
    args = p.parse_args()
    base = pathlib.Path(args.manifest).parent
    paths = [base / json.loads(line)["path"] for line in open(args.manifest) if line.strip()]
    run = run_pyrender if args.renderer == "pyrender" else run_open3d
    images, seconds, gl, last = run(paths, args.views, args.size)
    if args.image:
        from PIL import Image
        Image.fromarray(np.ascontiguousarray(last[..., :3])).save(args.image)
    print(json.dumps({"renderer": args.renderer, "gl": gl, "images": images, "seconds": seconds,
                      "images_per_second": images / seconds}))


if __name__ == "__main__":
    sys.exit(main())
