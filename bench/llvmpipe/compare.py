"""shadelab's tiled rasterizer against Mesa's llvmpipe, side by side.

Reads the standard scenes that `shadelab bench --export DIR` wrote (the exact
triangles, vertex normals, flat-shading inputs, camera, light and material)
and times each row with every llvmpipe given (Debian's Mesa, and others
selected by the `export` lines of `bench/mesa/fetch.sh`) and with
`shadelab bench --json`, in alternating rounds: each round runs every
llvmpipe and then shadelab, so that a stretch of load on a shared machine
weighs on all of them alike, and each keeps its median round.

Each llvmpipe runs in a worker process of its own (`llvmpipe.py`), since
one process can load only one Mesa: the worker makes an offscreen EGL context
(moderngl), compiles GLSL equivalent to shadelab's three methods, and
answers one JSON request per line on stdin with a JSON line on stdout.

Prints a markdown report: the side-by-side table with a ratio per Mesa,
the newest Mesa's ratio round by round, shadelab alone (1 and 2 threads,
Mtri/s, Mpix/s, cycles per pixel), how time grows with triangles and
pixels, and how often the images differ by more than 2/255 (llvmpipe as a
second correctness reference).

Run it through run.sh, which installs what it needs.
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
from pathlib import Path

import numpy as np
from PIL import Image

from llvmpipe import SHADINGS, Scene

class Mesa:
    """A worker process running one Mesa's llvmpipe (the coordinator's side)."""

    def __init__(self, scenes_dir, exports):
        env = dict(os.environ)
        env.setdefault("LP_NUM_THREADS", "2")
        for key, value in exports.items():
            env[key] = value
        self.process = subprocess.Popen(
            [sys.executable, str(Path(__file__).with_name("llvmpipe.py")), "--scenes", str(scenes_dir)],
            env=env, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True,
        )
        hello = self.read()
        self.renderer, self.version = hello["renderer"], hello["version"]
        if "llvmpipe" not in self.renderer:
            sys.exit(f"the GL renderer is {self.renderer!r}, not llvmpipe")
        # "4.5 (Core Profile) Mesa 25.0.7-2~bpo12+1" -> "25.0.7"
        words = self.version.split()
        full = words[words.index("Mesa") + 1] if "Mesa" in words else self.version
        self.name = "Mesa " + full.split("-")[0]
        self.short = "Mesa " + full.split(".")[0]
        self.threads = env["LP_NUM_THREADS"]

    def read(self):
        line = self.process.stdout.readline()
        if not line:
            sys.exit(f"an llvmpipe worker stopped (exit status {self.process.wait()})")
        return json.loads(line)

    def time(self, **request):
        self.process.stdin.write(json.dumps(request) + "\n")
        self.process.stdin.flush()
        return self.read()["ms"]

    def close(self):
        self.process.stdin.close()
        self.process.wait()


def parse_exports(path):
    """`export KEY=VALUE` lines (as bench/mesa/fetch.sh prints them) as a dict,
    with `${VAR:+:$VAR}` tails expanded from this environment."""
    exports = {}
    for line in Path(path).read_text().splitlines():
        line = line.strip()
        if not line.startswith("export "):
            continue
        key, value = line[len("export "):].split("=", 1)
        tail = "${" + key + ":+:$" + key + "}"
        if value.endswith(tail):
            value = value[: -len(tail)] + (":" + os.environ[key] if os.environ.get(key) else "")
        exports[key] = shlex.split(value)[0] if value else ""
    return exports


# A round trip above this (ns) means the two cores do not share a cache:
# about 50 ns beside each other, 400 ns or more apart (src/bench/cores.rs).
FAR_NS = 200


def shadelab_times(binary, model, size, shading, frames, warmup, warmup_time, models_dir):
    """Rows of `shadelab bench --json` for 1 and 2 threads, and its machine."""
    command = [
        str(binary), "bench", "--json", "--rasterizer", "tiled", "--threads", "1,2",
        "--model", model, "--size", size, "--shading", shading, "--frames", str(frames),
        "--warmup", str(warmup), "--warmup-time", str(warmup_time),
    ]
    if models_dir:
        command += ["--models-dir", str(models_dir)]
    out = json.loads(subprocess.run(command, check=True, capture_output=True, text=True).stdout)
    return {r["threads"]: r for r in out["rows"]}, out["machine"]


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


def nominal_mhz():
    """The `cpu MHz` /proc/cpuinfo reports (under a hypervisor, its TSC rate)."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("cpu MHz"):
                return float(line.split(":", 1)[1])
    except (OSError, ValueError):
        pass
    return None


def perf_counts_cycles():
    """Whether `perf stat -e cycles` can count cycles on this machine."""
    try:
        out = subprocess.run(
            ["perf", "stat", "-x,", "-e", "cycles", "true"], capture_output=True, text=True, timeout=30
        )
    except (OSError, subprocess.TimeoutExpired):
        return "perf is not installed"
    value = out.stderr.strip().splitlines()[-1].split(",")[0] if out.stderr.strip() else ""
    if value.replace(".", "").isdigit():
        return "available"
    return f"`perf stat -e cycles` says {value or 'nothing'!r}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenes", type=Path, required=True, help="what shadelab bench --export wrote")
    parser.add_argument("--shadelab", type=Path, help="the shadelab binary")
    parser.add_argument("--images", type=Path, help="where to save llvmpipe's images")
    parser.add_argument(
        "--mesa-env", type=Path, action="append", default=[],
        help="a file of `export` lines selecting another Mesa (bench/mesa/fetch.sh); repeatable."
        " Debian's Mesa (this process's environment) always runs first",
    )
    parser.add_argument("--models-dir", type=Path)
    parser.add_argument("--frames", type=int, default=31)
    parser.add_argument("--warmup", type=int, default=3, help="warm-up frames per row, at least")
    parser.add_argument(
        "--warmup-time", type=float, default=0.25,
        help="warm-up seconds per row, at least (a pool that was idle runs slowly at first)",
    )
    parser.add_argument("--budget", type=float, default=3.0, help="seconds per llvmpipe row at most")
    parser.add_argument(
        "--rounds", type=int, default=3,
        help="times each row is measured (each llvmpipe, then shadelab); the median round is reported",
    )
    parser.add_argument("--command", default="bash bench/llvmpipe/run.sh")
    args = parser.parse_args()
    if not args.shadelab or not args.images:
        parser.error("--shadelab and --images are required")

    mesas = [Mesa(args.scenes, {})] + [Mesa(args.scenes, parse_exports(p)) for p in args.mesa_env]
    args.images.mkdir(parents=True, exist_ok=True)
    stems = sorted(p.name[: -len(".json")] for p in args.scenes.glob("*.json"))
    order = {"sphere": 0, "teapot": 1, "bunny": 2, "dragon": 3, "quad": 4}
    stems.sort(key=lambda s: (order.get(s.split("-")[0], 9), int(s.split("-")[1].split("x")[0])))
    load_before = load_average()
    started = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    rows, machine = [], None
    for stem in stems:
        scene = Scene(args.scenes, stem)
        model = scene.info["model"]
        size = f'{scene.info["width"]}x{scene.info["height"]}'
        for shading in SHADINGS:
            ours_png = args.scenes / f"{stem}-{shading}.png"
            if not ours_png.exists():
                continue
            images = [args.images / f"{stem}-{shading}-llvmpipe-{m.short.split()[1]}.png" for m in mesas]
            gl_rounds = [[] for _ in mesas]
            ours_rounds, trips = [], []
            for _ in range(max(args.rounds, 1)):
                for mesa, rounds, image in zip(mesas, gl_rounds, images):
                    rounds.append(
                        mesa.time(
                            stem=stem, shading=shading, frames=args.frames, warmup=args.warmup,
                            warmup_time=args.warmup_time,
                            budget=args.budget, image=str(image),
                        )
                    )
                ours, machine = shadelab_times(
                    args.shadelab, model, size, shading, args.frames, args.warmup, args.warmup_time,
                    args.models_dir,
                )
                ours_rounds.append(ours)
                trips.append(machine.get("round_trip_ns"))
            ours_pixels = np.asarray(Image.open(ours_png).convert("RGB")).astype(int)
            background = np.array(scene.info["background"], dtype=np.uint8)
            differ, drawn = [], []
            for image in images:
                gl_pixels = np.asarray(Image.open(image).convert("RGB"))
                differ.append(int((np.abs(ours_pixels - gl_pixels.astype(int)) > 2).any(axis=2).sum()))
                drawn.append(
                    int(((ours_pixels != background).any(axis=2) | (gl_pixels != background).any(axis=2)).sum())
                )
            median = lambda threads, key: statistics.median(o[threads][key] for o in ours_rounds)  # noqa: E731
            rows.append(
                {
                    "model": model,
                    "triangles": scene.info["triangles"],
                    "size": size,
                    "width": scene.info["width"],
                    "height": scene.info["height"],
                    "shading": shading,
                    "gl_ms": [statistics.median(r) for r in gl_rounds],
                    "gl_rounds": gl_rounds,
                    "ours_1": median(1, "median_ms"),
                    "ours_2": median(2, "median_ms"),
                    "ours_rounds": [o[2]["median_ms"] for o in ours_rounds],
                    "round_trips": trips,
                    "covered": ours_rounds[0][2]["covered_pixels"],
                    "differ": differ,
                    "drawn": drawn,
                    "pixels": scene.info["width"] * scene.info["height"],
                }
            )
            r = rows[-1]
            against = "  ".join(
                f"{m.short} {ms:7.2f} ms ({ms / r['ours_2']:5.2f}×)" for m, ms in zip(mesas, r["gl_ms"])
            )
            print(f"{model:7} {size:>9} {shading:8} shadelab {r['ours_2']:7.2f} ms  {against}", file=sys.stderr)
    for mesa in mesas:
        mesa.close()
    load_after = load_average()
    report(args, mesas, rows, machine or {}, started, load_before, load_after)


def round_by_round(p, newest, rows):
    """Each row's ratio against the newest Mesa in every round, their median,
    and how many reached 3×: a round's two times were taken one after the
    other, so a slow spell of a shared machine weighs on both, where the
    ratio of the two medians can pair a fast round of one with a slow round
    of the other."""
    p(f"### Round by round against {newest.name}")
    p("")
    p(
        f"A round's ratio is its {newest.name} median over its shadelab median (2 threads), timed one"
        " after the other."
    )
    p("")
    p(
        "The rounds' round trips are those `shadelab bench` measured as it started (a cache line between"
        " two threads, `src/bench/cores.rs`): about 50 ns where the host ran the two virtual cores"
        " beside each other, 400–650 ns where it put them apart, microseconds where they took turns"
        " on one core."
    )
    p("")
    p("| model | size | shading | the rounds' ratios | median | rounds at 3× or more | the rounds' round trips, ns |")
    p("|---|---|---|---|---:|---:|---|")
    met = 0
    for r in rows:
        ratios = [gl / ours for gl, ours in zip(r["gl_rounds"][-1], r["ours_rounds"])]
        median = statistics.median(ratios)
        met += median >= 3
        p(
            f"| {r['model']} | {r['size']} | {r['shading']} | {' '.join(f'{x:.2f}' for x in ratios)} "
            f"| {median:.2f}× | {sum(x >= 3 for x in ratios)} of {len(ratios)} "
            f"| {' '.join(trip_text(t) for t in r['round_trips'])} |"
        )
    p("")
    p(f"Rows whose median round is at 3× or more: {met} of {len(rows)}.")
    p("")


def trip_text(ns):
    """A round trip in ns for the tables ("–" where none was measured)."""
    return "–" if ns is None else f"{ns:.0f}"


def round_trips_line(rows):
    """What the host did with the two cores over the run, from the round
    trips each shadelab call measured."""
    trips = [t for r in rows for t in r["round_trips"] if t is not None]
    if not trips:
        return "No round trip between cores was measured (one core)."
    far = sum(t > FAR_NS for t in trips)
    return (
        f"A cache line's round trip between two cores, measured as each of the {len(trips)} shadelab calls"
        f" started: {min(trips):.0f}–{max(trips):.0f} ns, median {statistics.median(trips):.0f};"
        f" above {FAR_NS} ns (the host running the two virtual cores apart) in {far} of them."
    )


def report(args, mesas, rows, machine, started, load_before, load_after):
    out = []
    p = out.append
    newest = mesas[-1]
    p(f"Measured {started} on {cpu_name()}, {os.cpu_count()} cores;")
    p(f"load average (1, 5, 15 min) {' '.join(load_before)} before, {' '.join(load_after)} after.")
    p(round_trips_line(rows))
    for m in mesas:
        p(f"{m.name}: `{m.renderer}`, OpenGL {m.version}, LP_NUM_THREADS={m.threads}.")
    p(
        f"Command: `{args.command}`. Median ms per frame of up to {args.frames} frames after at least {args.warmup} warm-up frames"
        f" and {args.warmup_time} s of them (each side);"
        f" each row measured in {args.rounds} alternating rounds ({', '.join(m.name for m in mesas)}, then shadelab),"
        " the median round of each kept."
    )
    p("llvmpipe's frame is clear + draw + glFinish; shadelab's is `Renderer::render_into` (clear, draw, RGB image), called on one of the pool's threads, as `shadelab batch` renders.")
    p("")
    p(f"### shadelab (tiled, 2 threads) against llvmpipe (2 threads), {' and '.join(m.name for m in mesas)}")
    p("")
    head = " | ".join(f"{m.name} ms" for m in mesas)
    ratios = " | ".join(f"× {m.short}" for m in mesas)
    p(f"| model | triangles | size | shading | {head} | shadelab ms | {ratios} | ≥ 3× {newest.short} |")
    p("|---|---:|---|---|" + "---:|" * len(mesas) + "---:|" + "---:|" * len(mesas) + ":-:|")
    for r in rows:
        times = " | ".join(f"{ms:.2f}" for ms in r["gl_ms"])
        ratio = " | ".join(f"{ms / r['ours_2']:.2f}×" for ms in r["gl_ms"])
        met = r["gl_ms"][-1] / r["ours_2"] >= 3
        p(
            f"| {r['model']} | {r['triangles']:,} | {r['size']} | {r['shading']} | {times} "
            f"| {r['ours_2']:.2f} | {ratio} | {'yes' if met else '**no**'} |"
        )
    p("")
    p("ratio = llvmpipe's time / shadelab's time. " + "; ".join(
        f"against {m.name}: {sum(1 for r in rows if r['gl_ms'][i] / r['ours_2'] >= 3)} of {len(rows)} rows"
        f" at 3× or more, {sum(1 for r in rows if r['gl_ms'][i] / r['ours_2'] >= 5)} at 5×"
        for i, m in enumerate(mesas)
    ) + ".")
    p("")
    round_by_round(p, newest, rows)
    clock = machine.get("clock_mhz")
    nominal = nominal_mhz()
    p("### shadelab alone: threads, throughput, cycles per pixel")
    p("")
    p(
        "Medians of the same rounds. Mtri/s and Mpix/s at 2 threads (Mpix/s counts the pixels drawn);"
        " cycles per pixel = one thread's time × the clock / pixels drawn, the work of one core per pixel"
        f" at a clock of {clock:.0f} MHz, measured by `shadelab bench` with a chain of dependent multiply-adds"
        f" (/proc/cpuinfo says {nominal:.0f} MHz; the cycle counters: {perf_counts_cycles()})."
        if clock and nominal
        else "Mtri/s and Mpix/s at 2 threads; no clock was measured, so no cycles per pixel."
    )
    p("")
    p("| model | triangles | size | shading | 1 thread ms | 2 threads ms | 2 threads / 1 | Mtri/s | Mpix/s | cycles/px |")
    p("|---|---:|---|---|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        cycles = f"{r['ours_1'] * 1e3 * clock / max(r['covered'], 1):.1f}" if clock else "–"
        p(
            f"| {r['model']} | {r['triangles']:,} | {r['size']} | {r['shading']} | {r['ours_1']:.2f} "
            f"| {r['ours_2']:.2f} | {r['ours_1'] / r['ours_2']:.2f}× | {r['triangles'] / r['ours_2'] / 1e3:.1f} "
            f"| {r['covered'] / r['ours_2'] / 1e3:,.0f} | {cycles} |"
        )
    p("")
    by = {(r["model"], r["size"], r["shading"]): r for r in rows}
    goals = []
    quad_phong = by.get(("quad", "1920x1080", "phong"))
    if quad_phong:
        goals.append(
            f"full-screen Phong at 1920×1080 fills {quad_phong['covered'] / quad_phong['ours_2'] / 1e3:,.0f} Mpix/s"
            " (goal: 1,000)"
        )
    for size in ("512x512", "1920x1080"):
        flat, gouraud = by.get(("quad", size, "flat")), by.get(("quad", size, "gouraud"))
        if flat and gouraud:
            goals.append(
                f"the Gouraud quad at {size.replace('x', '×')} takes {gouraud['ours_2'] / flat['ours_2']:.2f}×"
                " the flat one's time (goal: 1.2× at most)"
            )
    big = [r for r in rows if r["size"] == "1920x1080" and r["model"] in ("bunny", "dragon", "quad")]
    if big:
        speedups = [r["ours_1"] / r["ours_2"] for r in big]
        goals.append(
            f"2 threads against 1 on the {len(big)} rows at 1920×1080: {min(speedups):.2f}–{max(speedups):.2f}×,"
            f" {sum(1 for s in speedups if s >= 1.8)} of {len(big)} at 1.8× or more"
        )
    if goals:
        p("Goals of the fill: " + "; ".join(goals) + ".")
        p("")
    phong = {(r["model"], r["size"]): r for r in rows if r["shading"] == "phong"}
    models = sorted({r["model"] for r in rows}, key=lambda m: next(r["triangles"] for r in rows if r["model"] == m))
    growth = [(m, phong.get((m, "512x512")), phong.get((m, "1920x1080"))) for m in models]
    growth = [g for g in growth if g[1] and g[2]]
    if growth:
        p("### How time grows (shadelab, 2 threads, Phong)")
        p("")
        p("| model | triangles | 512×512 ms | 1920×1080 ms | covered px at 1080p | 1080p / 512 |")
        p("|---|---:|---:|---:|---:|---:|")
        for m, small, big in growth:
            p(
                f"| {m} | {small['triangles']:,} | {small['ours_2']:.2f} | {big['ours_2']:.2f} "
                f"| {big['covered']:,} | {big['ours_2'] / small['ours_2']:.2f}× |"
            )
        p("")
    p("### The same scene drawn by both: pixels differing by more than 2/255 in a channel")
    p("")
    p("| model | size | shading | " + " | ".join(f"differing from {m.name} (of drawn pixels)" for m in mesas) + " |")
    p("|---|---|---|" + "---:|" * len(mesas))
    for r in rows:
        cells = " | ".join(
            f"{d:,} ({d / max(n, 1):.3%})" for d, n in zip(r["differ"], r["drawn"])
        )
        p(f"| {r['model']} | {r['size']} | {r['shading']} | {cells} |")
    p("")
    p(
        "Rounds (ms; "
        + ", ".join(m.name for m in mesas)
        + ", shadelab at 2 threads): "
        + json.dumps(
            {
                f"{r['model']} {r['size']} {r['shading']}": [[round(x, 2) for x in g] for g in r["gl_rounds"]]
                + [[round(x, 2) for x in r["ours_rounds"]]]
                for r in rows
            }
        )
    )
    print("\n".join(out))


if __name__ == "__main__":
    main()
