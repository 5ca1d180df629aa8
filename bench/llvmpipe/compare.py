"""shadelab's tiled rasterizer against Mesa's llvmpipe, side by side.

Reads the standard scenes that `shadelab bench --export DIR` wrote (the exact
triangles, vertex normals, flat-shading inputs, camera, light and material),
renders each with llvmpipe through an offscreen EGL context (moderngl) using
GLSL shaders equivalent to shadelab's three methods, and times it; right
after each llvmpipe row, times the same row with `shadelab bench --json`, so
the two alternate under the same machine load. Prints a markdown report:
the side-by-side table with ratios, shadelab's 1-vs-2-thread scaling, how
time grows with triangles and pixels, and how often the two images differ
by more than 2/255 (llvmpipe as a second correctness reference).

Run it through run.sh, which installs what it needs.
"""

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path

# llvmpipe reads its thread count when the context is created.
os.environ.setdefault("LP_NUM_THREADS", "2")

import moderngl  # noqa: E402
import numpy as np  # noqa: E402
from PIL import Image  # noqa: E402

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
    def __init__(self):
        self.ctx = moderngl.create_standalone_context(backend="egl")
        self.renderer = self.ctx.info["GL_RENDERER"]
        self.version = self.ctx.info["GL_VERSION"]
        if "llvmpipe" not in self.renderer:
            sys.exit(f"the GL renderer is {self.renderer!r}, not llvmpipe")
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
        self.ctx.enable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        self.ctx.front_face = "ccw"
        self.ctx.cull_face = "back"
        fbo.clear(*background, 1.0, depth=1.0)
        vao.render(moderngl.TRIANGLES)
        self.ctx.finish()

    def time(self, scene, shading, frames, warmup, budget):
        fbo, vao = self.prepare(scene, shading)
        background = [v / 255.0 for v in scene.info["background"]]
        for _ in range(warmup):
            self.frame(fbo, vao, background)
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


def shadelab_times(binary, model, size, shading, frames, models_dir):
    """Median ms for 1 and 2 threads, from `shadelab bench --json`."""
    command = [
        str(binary), "bench", "--json", "--rasterizer", "tiled", "--threads", "1,2",
        "--model", model, "--size", size, "--shading", shading, "--frames", str(frames),
    ]
    if models_dir:
        command += ["--models-dir", str(models_dir)]
    out = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    rows = json.loads(out)["rows"]
    return {r["threads"]: r for r in rows}


def load_average():
    try:
        return Path("/proc/loadavg").read_text().split()[:3]
    except OSError:
        return ["?", "?", "?"]


def cpu_name():
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", type=Path, required=True, help="what shadelab bench --export wrote")
    parser.add_argument("--shadelab", type=Path, required=True, help="the shadelab binary")
    parser.add_argument("--images", type=Path, required=True, help="where to save llvmpipe's images")
    parser.add_argument("--models-dir", type=Path)
    parser.add_argument("--frames", type=int, default=31)
    parser.add_argument("--warmup", type=int, default=3)
    parser.add_argument("--budget", type=float, default=3.0, help="seconds per llvmpipe row at most")
    parser.add_argument(
        "--rounds", type=int, default=3,
        help="times each row is measured (llvmpipe, then shadelab); the median round is reported",
    )
    parser.add_argument("--command", default="bash bench/llvmpipe/run.sh")
    args = parser.parse_args()

    gl = Llvmpipe()
    args.images.mkdir(parents=True, exist_ok=True)
    stems = sorted(p.name[: -len(".json")] for p in args.scenes.glob("*.json"))
    order = {"sphere": 0, "teapot": 1, "bunny": 2, "dragon": 3, "quad": 4}
    stems.sort(key=lambda s: (order.get(s.split("-")[0], 9), -int(s.split("-")[1].split("x")[0])))
    load_before = load_average()
    rows = []
    for stem in stems:
        scene = Scene(args.scenes, stem)
        model = scene.info["model"]
        size = f'{scene.info["width"]}x{scene.info["height"]}'
        for shading in ("flat", "gouraud", "phong"):
            ours_png = args.scenes / f"{stem}-{shading}.png"
            if not ours_png.exists():
                continue
            # Rounds alternate the two renderers, so that a stretch of load on
            # a shared machine weighs on both; each takes its median round.
            gl_rounds, ours_rounds = [], []
            for _ in range(max(args.rounds, 1)):
                gl_ms, gl_pixels = gl.time(scene, shading, args.frames, args.warmup, args.budget)
                gl_rounds.append(gl_ms)
                ours_rounds.append(
                    shadelab_times(args.shadelab, model, size, shading, args.frames, args.models_dir)
                )
            gl_ms = statistics.median(gl_rounds)
            ours = {
                threads: {
                    "median_ms": statistics.median(o[threads]["median_ms"] for o in ours_rounds),
                    "covered_pixels": ours_rounds[0][threads]["covered_pixels"],
                }
                for threads in (1, 2)
            }
            Image.fromarray(gl_pixels).save(args.images / f"{stem}-{shading}-llvmpipe.png")
            ours_pixels = np.asarray(Image.open(ours_png).convert("RGB"))
            differ = (np.abs(ours_pixels.astype(int) - gl_pixels.astype(int)) > 2).any(axis=2)
            background = np.array(scene.info["background"], dtype=np.uint8)
            drawn = (ours_pixels != background).any(axis=2) | (gl_pixels != background).any(axis=2)
            rows.append(
                {
                    "model": model,
                    "triangles": scene.info["triangles"],
                    "size": size,
                    "shading": shading,
                    "llvmpipe_ms": gl_ms,
                    "ours_1": ours[1]["median_ms"],
                    "ours_2": ours[2]["median_ms"],
                    "covered": ours[2]["covered_pixels"],
                    "differ": int(differ.sum()),
                    "drawn": int(drawn.sum()),
                    "pixels": differ.size,
                }
            )
            r = rows[-1]
            print(
                f"{model:7} {size:>9} {shading:8} llvmpipe {gl_ms:8.2f} ms  shadelab {r['ours_2']:7.2f} ms"
                f"  ratio {gl_ms / r['ours_2']:5.2f}  differ {r['differ'] / r['pixels']:.4%}",
                file=sys.stderr,
            )
    load_after = load_average()
    report(args, gl, rows, load_before, load_after)


def report(args, gl, rows, load_before, load_after):
    out = []
    p = out.append
    p(f"Measured {time.strftime('%Y-%m-%d %H:%M %Z')} on {cpu_name()}, {os.cpu_count()} cores;")
    p(f"load average (1, 5, 15 min) {' '.join(load_before)} before, {' '.join(load_after)} after.")
    p(f"llvmpipe: `{gl.renderer}`, OpenGL {gl.version}, LP_NUM_THREADS={os.environ['LP_NUM_THREADS']}.")
    p(
        f"Command: `{args.command}`. Median ms per frame of up to {args.frames} frames after {args.warmup} warm-up,"
        f" each row measured in {args.rounds} alternating rounds (llvmpipe, shadelab) and the median round kept;"
    )
    p("llvmpipe's frame is clear + draw + glFinish; shadelab's is `Renderer::render_into` (clear, draw, RGB image).")
    p("")
    p("### shadelab (tiled, 2 threads) against llvmpipe (2 threads)")
    p("")
    p("| model | triangles | size | shading | llvmpipe ms | shadelab ms | ratio | ≥ 3× |")
    p("|---|---:|---|---|---:|---:|---:|:-:|")
    for r in rows:
        ratio = r["llvmpipe_ms"] / r["ours_2"]
        p(
            f"| {r['model']} | {r['triangles']:,} | {r['size']} | {r['shading']} | {r['llvmpipe_ms']:.2f} "
            f"| {r['ours_2']:.2f} | {ratio:.2f}× | {'yes' if ratio >= 3 else '**no**'} |"
        )
    p("")
    met = sum(1 for r in rows if r["llvmpipe_ms"] / r["ours_2"] >= 3)
    p(f"ratio = llvmpipe's time / shadelab's time; {met} of {len(rows)} rows at 3× or more.")
    p("")
    p("### Threads: shadelab with 1 and 2 threads")
    p("")
    p("| model | size | shading | 1 thread ms | 2 threads ms | speed-up |")
    p("|---|---|---|---:|---:|---:|")
    for r in rows:
        p(
            f"| {r['model']} | {r['size']} | {r['shading']} | {r['ours_1']:.2f} | {r['ours_2']:.2f} "
            f"| {r['ours_1'] / r['ours_2']:.2f}× |"
        )
    p("")
    p("### How time grows (shadelab, 2 threads, Phong)")
    p("")
    p("| model | triangles | 512×512 ms | 1920×1080 ms | covered px at 1080p | 1080p / 512 |")
    p("|---|---:|---:|---:|---:|---:|")
    phong = {(r["model"], r["size"]): r for r in rows if r["shading"] == "phong"}
    models = sorted({r["model"] for r in rows}, key=lambda m: next(r["triangles"] for r in rows if r["model"] == m))
    for m in models:
        small, big = phong.get((m, "512x512")), phong.get((m, "1920x1080"))
        if small and big:
            p(
                f"| {m} | {small['triangles']:,} | {small['ours_2']:.2f} | {big['ours_2']:.2f} "
                f"| {big['covered']:,} | {big['ours_2'] / small['ours_2']:.2f}× |"
            )
    p("")
    p("### The same scene drawn by both: pixels differing by more than 2/255 in a channel")
    p("")
    p("| model | size | shading | differing pixels | of all pixels | of drawn pixels |")
    p("|---|---|---|---:|---:|---:|")
    for r in rows:
        p(
            f"| {r['model']} | {r['size']} | {r['shading']} | {r['differ']:,} | {r['differ'] / r['pixels']:.3%} "
            f"| {r['differ'] / max(r['drawn'], 1):.3%} |"
        )
    print("\n".join(out))


if __name__ == "__main__":
    main()
