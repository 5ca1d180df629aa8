"""The llvmpipe side of compare.py: one Mesa's llvmpipe in this process.

Run by compare.py as a worker process (`python3 llvmpipe.py --scenes DIR`),
one per Mesa, since one process can load only one Mesa. It makes an offscreen
EGL context (moderngl), compiles GLSL equivalent to shadelab's three methods
(the shaders below), says which renderer it got in a first JSON line, and then
answers one JSON request per line on stdin (a scene, a method, how many
frames) with a JSON line on stdout (the median ms), saving the image it drew.
"""

import argparse
import json
import statistics
import sys
import time
from pathlib import Path

import numpy as np
from PIL import Image

VERTEX_PHONG = """
#version 330
uniform mat4 mvp;
in vec3 in_position;
in vec3 in_normal;
out vec3 v_position;
out vec3 v_normal;
void main() {
    v_position = in_position;
    v_normal = in_normal;
    gl_Position = mvp * vec4(in_position, 1.0);
}
"""

# The reflection model, as shadelab's Lighting::eval (one point light).
LIGHTING = """
uniform vec3 eye;
uniform vec3 light_position;
uniform vec3 ambient;   // Ia*Ka
uniform vec3 diffuse;   // Id*Kd
uniform vec3 specular;  // Is*Ks
uniform float shininess;
vec3 reflect_light(vec3 p, vec3 n, bool with_specular) {
    vec3 c = ambient;
    vec3 l = normalize(light_position - p);
    float n_dot_l = dot(n, l);
    if (n_dot_l > 0.0) {
        c += diffuse * n_dot_l;
        if (with_specular) {
            vec3 v = normalize(eye - p);
            vec3 r = 2.0 * n_dot_l * n - l;
            c += specular * pow(max(dot(r, v), 0.0), shininess);
        }
    }
    return c;
}
"""

FRAGMENT_PHONG = """
#version 330
""" + LIGHTING + """
in vec3 v_position;
in vec3 v_normal;
out vec4 f_color;
void main() {
    f_color = vec4(clamp(reflect_light(v_position, normalize(v_normal), true), 0.0, 1.0), 1.0);
}
"""

VERTEX_GOURAUD = """
#version 330
""" + LIGHTING + """
uniform mat4 mvp;
in vec3 in_position;
in vec3 in_normal;
out vec3 v_color;
void main() {
    v_color = clamp(reflect_light(in_position, in_normal, false), 0.0, 1.0);
    gl_Position = mvp * vec4(in_position, 1.0);
}
"""

FRAGMENT_COLOR = """
#version 330
in vec3 v_color;
out vec4 f_color;
void main() {
    f_color = vec4(v_color, 1.0);
}
"""

# Flat: each corner carries its polygon's face normal and centroid; the
# provoking vertex's colour, lit at the centroid, fills the triangle.
VERTEX_FLAT = """
#version 330
""" + LIGHTING + """
uniform mat4 mvp;
in vec3 in_position;
in vec3 in_face_normal;
in vec3 in_centroid;
flat out vec3 v_color;
void main() {
    v_color = clamp(reflect_light(in_centroid, in_face_normal, true), 0.0, 1.0);
    gl_Position = mvp * vec4(in_position, 1.0);
}
"""

FRAGMENT_FLAT = """
#version 330
flat in vec3 v_color;
out vec4 f_color;
void main() {
    f_color = vec4(v_color, 1.0);
}
"""

SHADINGS = ("flat", "gouraud", "phong")


def perspective(fov_y_degrees, aspect, near, far):
    """gluPerspective, as glam's Mat4::perspective_rh_gl."""
    f = 1.0 / np.tan(np.radians(fov_y_degrees) / 2.0)
    return np.array(
        [
            [f / aspect, 0, 0, 0],
            [0, f, 0, 0],
            [0, 0, (far + near) / (near - far), 2 * far * near / (near - far)],
            [0, 0, -1, 0],
        ],
        dtype=np.float64,
    )


def look_at(eye, target, up):
    """gluLookAt, as glam's Mat4::look_at_rh."""
    eye, target, up = (np.array(v, dtype=np.float64) for v in (eye, target, up))
    f = target - eye
    f /= np.linalg.norm(f)
    s = np.cross(f, up)
    s /= np.linalg.norm(s)
    u = np.cross(s, f)
    m = np.identity(4)
    m[0, :3], m[1, :3], m[2, :3] = s, u, -f
    m[0, 3], m[1, 3], m[2, 3] = -s @ eye, -u @ eye, f @ eye
    return m


class Scene:
    """One exported standard scene (a model at one size)."""

    def __init__(self, directory, stem):
        self.stem = stem
        self.info = json.loads((directory / f"{stem}.json").read_text())
        self.vertices = np.fromfile(directory / f"{stem}.vertices.f32", dtype="<f4")
        self.indices = np.fromfile(directory / f"{stem}.indices.u32", dtype="<u4")
        self.flat = np.fromfile(directory / f"{stem}.flat.f32", dtype="<f4").reshape(-1, 6)
        self.directory = directory


class Llvmpipe:
    """An llvmpipe context in this process (the worker's side)."""

    def __init__(self):
        import moderngl

        self.gl = moderngl
        self.ctx = moderngl.create_standalone_context(backend="egl")
        self.renderer = self.ctx.info["GL_RENDERER"]
        self.version = self.ctx.info["GL_VERSION"]
        self.programs = {
            "phong": self.ctx.program(vertex_shader=VERTEX_PHONG, fragment_shader=FRAGMENT_PHONG),
            "gouraud": self.ctx.program(vertex_shader=VERTEX_GOURAUD, fragment_shader=FRAGMENT_COLOR),
            "flat": self.ctx.program(vertex_shader=VERTEX_FLAT, fragment_shader=FRAGMENT_FLAT),
        }

    def prepare(self, scene, shading):
        """The framebuffer and vertex array for one row."""
        info = scene.info
        w, h = info["width"], info["height"]
        ctx = self.ctx
        fbo = ctx.framebuffer(
            color_attachments=[ctx.renderbuffer((w, h), components=4)],
            depth_attachment=ctx.depth_renderbuffer((w, h)),
        )
        program = self.programs[shading]
        mvp = perspective(info["fov_y"], w / h, info["near"], info["far"]) @ look_at(
            info["eye"], info["target"], info["up"]
        )
        program["mvp"].write(mvp.T.astype("f4").tobytes())
        c = lambda key: np.array(info[key], dtype=np.float64) / 255.0  # noqa: E731
        light = c("light_color")
        uniforms = {
            "eye": info["eye"],
            "light_position": info["light"],
            "ambient": c("ambient") * info["ambient_intensity"] * c("ka"),
            "diffuse": light * c("kd"),
            "specular": light * c("ks"),
            "shininess": info["shininess"],
        }
        for name, value in uniforms.items():
            if name in program:
                program[name].value = tuple(value) if np.ndim(value) else float(value)
        if shading == "flat":
            corners = scene.vertices.reshape(-1, 6)[scene.indices, :3]
            per_corner = np.repeat(scene.flat, 3, axis=0)
            data = np.hstack([corners, per_corner]).astype("f4")
            vbo = ctx.buffer(data.tobytes())
            vao = ctx.vertex_array(
                program, [(vbo, "3f 3f 3f", "in_position", "in_face_normal", "in_centroid")]
            )
        else:
            vbo = ctx.buffer(scene.vertices.astype("f4").tobytes())
            ibo = ctx.buffer(scene.indices.astype("u4").tobytes())
            vao = ctx.vertex_array(
                program, [(vbo, "3f 3f", "in_position", "in_normal")], index_buffer=ibo, index_element_size=4
            )
        return fbo, vao

    def frame(self, fbo, vao, background):
        fbo.use()
        self.ctx.enable(self.gl.DEPTH_TEST | self.gl.CULL_FACE)
        self.ctx.front_face = "ccw"
        self.ctx.cull_face = "back"
        fbo.clear(*background, 1.0, depth=1.0)
        vao.render(self.gl.TRIANGLES)
        self.ctx.finish()

    def time(self, scene, shading, frames, warmup, warmup_time, budget):
        """Median ms per frame, and the last frame's pixels (top row first).
        Warm-up: `warmup` frames and at least `warmup_time` seconds, as shadelab's."""
        fbo, vao = self.prepare(scene, shading)
        background = [v / 255.0 for v in scene.info["background"]]
        warm, start = 0, time.perf_counter()
        while warm < warmup or time.perf_counter() - start < warmup_time:
            self.frame(fbo, vao, background)
            warm += 1
        times = []
        start = time.perf_counter()
        while len(times) < frames and (len(times) < 3 or time.perf_counter() - start < budget):
            t = time.perf_counter()
            self.frame(fbo, vao, background)
            times.append((time.perf_counter() - t) * 1e3)
        w, h = scene.info["width"], scene.info["height"]
        pixels = np.frombuffer(fbo.read(components=3), dtype=np.uint8).reshape(h, w, 3)[::-1]
        fbo.release()
        vao.release()
        return statistics.median(times), pixels


def worker(scenes_dir):
    """Serves timing requests on stdin, one JSON object per line."""
    out = sys.stdout
    sys.stdout = sys.stderr  # nothing else may write to the protocol's stream
    gl = Llvmpipe()
    print(json.dumps({"renderer": gl.renderer, "version": gl.version}), file=out, flush=True)
    scenes = {}
    for line in sys.stdin:
        request = json.loads(line)
        stem = request["stem"]
        if stem not in scenes:
            scenes = {stem: Scene(scenes_dir, stem)}  # one scene's arrays at a time
        ms, pixels = gl.time(
            scenes[stem], request["shading"], request["frames"], request["warmup"],
            request["warmup_time"], request["budget"],
        )
        Image.fromarray(np.ascontiguousarray(pixels)).save(request["image"])
        print(json.dumps({"ms": ms}), file=out, flush=True)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", type=Path, required=True, help="what shadelab bench --export wrote")
    worker(parser.parse_args().scenes)
