"""Runs the rounds of bench/batch/run.sh and prints the markdown table.

Each round runs every contender once, in the same order: `shadelab batch`
(the CLI), `shadelab.batch` (Python), a Python loop of `shadelab.render` on
two threads, then pyrender and Open3D on Mesa 22 and on Mesa 25. The median
round of each is kept, so load that comes and goes touches all alike.
"""

import argparse
import json
import os
import platform
import shlex
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def load_average():
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


def timed(cmd, env=None):
    start = time.perf_counter()
    try:
        out = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=1200)
    except subprocess.TimeoutExpired:
        return None, ["did not finish in 20 minutes"]
    seconds = time.perf_counter() - start
    if out.returncode != 0:
        return None, out.stderr.strip().splitlines()[-3:]
    return seconds, out


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--manifest", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--shadelab", required=True)
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--views", type=int, default=6)
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--mesa25", required=True, help="the export lines of bench/mesa/fetch.sh")
    p.add_argument("--open3d", default="1")
    p.add_argument("--command", default="bash bench/batch/run.sh")
    a = p.parse_args()

    meshes = sum(1 for line in open(a.manifest) if line.strip())
    images = meshes * a.views
    size = f"{a.size}x{a.size}"
    out = os.path.join(a.work, "out")
    py = sys.executable
    env22 = dict(os.environ, LP_NUM_THREADS="2", PYOPENGL_PLATFORM="egl", EGL_PLATFORM="surfaceless",
                 OPEN3D_CPU_RENDERING="true")
    env25 = dict(env22)
    for line in a.mesa25.splitlines():
        key, value = line.removeprefix("export ").split("=", 1)
        env25[key] = os.path.expandvars(value.replace("${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}", ""))

    cli = [a.shadelab, "batch", a.manifest, "-o", out, "--views", str(a.views), "--size", size,
           "--shading", "phong", "--force", "--progress", "none"]
    pybatch = [py, "-c", (
        "import shadelab, sys; s = shadelab.batch(sys.argv[1], sys.argv[2], views=int(sys.argv[3]), "
        "size=(int(sys.argv[4]),) * 2, shading='phong', force=True); assert s['written'] == s['meshes'] * int(sys.argv[3])"
    ), a.manifest, out + "-py", str(a.views), str(a.size)]
    pyrender_loop = [py, os.path.join(HERE, "render_loop.py"), a.manifest, "--views", str(a.views),
                     "--size", str(a.size), "--threads", "2"]
    contenders = [
        ("shadelab batch (CLI)", "-", cli, None),
        ("shadelab.batch (Python)", "-", pybatch, None),
        ("shadelab.render loop (Python, 2 threads, no PNG)", "-", pyrender_loop, None),
    ]
    others = [("pyrender", "pyrender (EGL)")] + ([("open3d", "Open3D OffscreenRenderer")] if a.open3d == "1" else [])
    for name, title in others:
        for mesa, env in (("22.3.6", env22), ("25.0.7", env25)):
            cmd = [py, os.path.join(HERE, "others.py"), name, a.manifest, "--views", str(a.views),
                   "--size", str(a.size), "--image", os.path.join(a.work, f"{name}-{mesa}.png")]
            contenders.append((title, mesa, cmd, env))

    times = {(t, m): [] for t, m, _, _ in contenders}
    notes = {}
    load_before = load_average()
    started = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    for r in range(a.rounds):
        for title, mesa, cmd, env in contenders:
            seconds, result = timed(cmd, env)
            if seconds is None:
                notes[(title, mesa)] = " / ".join(result)
                print(f"round {r + 1}: {title} {mesa}: failed: {notes[(title, mesa)]}", file=sys.stderr)
                continue
            if cmd[0] == py and cmd[1].endswith(("others.py", "render_loop.py")):
                info = json.loads(result.stdout.strip().splitlines()[-1])
                if "gl" in info:
                    notes[(title, mesa)] = info["gl"].replace(" | ", ", ")
                assert info["images"] == images, info
                seconds = info["seconds"]  # its own clock: without Python's and the library's start-up
            times[(title, mesa)].append(seconds)
            print(f"round {r + 1}: {title} {mesa}: {images / seconds:.1f} images/s ({seconds:.2f} s)",
                  file=sys.stderr)
    load_after = load_average()

    def rate(key):
        return images / statistics.median(times[key]) if times[key] else None

    base = rate(("pyrender (EGL)", "25.0.7"))
    cpu = "unknown CPU"
    try:
        cpu = next(l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name"))
    except (OSError, StopIteration):
        pass
    print(f"Measured {started} on {cpu}, {os.cpu_count()} cores, {platform.system()};")
    print(f"load average (1, 5, 15 min) {load_before} before, {load_after} after.")
    print(f"Command: `{a.command}`. {meshes} meshes × {a.views} views = {images} images of {size}, Phong;"
          f" the median of {a.rounds} alternating rounds. llvmpipe with LP_NUM_THREADS=2.")
    print()
    print("| renderer | Mesa | GL_RENDERER | images/s | × pyrender on Mesa 25 |")
    print("|---|---|---|---:|---:|")
    for title, mesa, _, _ in contenders:
        key = (title, mesa)
        r = rate(key)
        gl = notes.get(key, "–") if mesa != "-" else "none (CPU rasterizer)"
        if r is None:
            print(f"| {title} | {mesa} | failed: {gl} | – | – |")
        else:
            ratio = f"{r / base:.2f}×" if base else "–"
            print(f"| {title} | {mesa} | {gl} | {r:.1f} | {ratio} |")
    cli_rate, py_rate = rate(("shadelab batch (CLI)", "-")), rate(("shadelab.batch (Python)", "-"))
    if cli_rate and py_rate:
        print()
        print(f"Python's `shadelab.batch` runs at {100 * py_rate / cli_rate:.1f} % of the CLI's rate.")
    print()
    print("Rounds (s):", json.dumps({f"{t} {m}": [round(x, 2) for x in v] for (t, m), v in times.items()}))


if __name__ == "__main__":
    main()
