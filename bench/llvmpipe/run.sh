#!/usr/bin/env bash
# shadelab against Mesa's llvmpipe on the standard scenes, side by side:
# Debian's Mesa 22 and Mesa 25.0.7 from bookworm-backports (fetched into
# target/mesa-25 by bench/mesa/fetch.sh, nothing in /etc changed), each in
# a worker process of its own, in alternating rounds with shadelab.
# Installs what it needs (Debian's Mesa EGL driver, a Python venv with
# moderngl, numpy and Pillow), builds shadelab, exports the scenes, and
# prints the markdown tables of BENCHMARKS.md to stdout (progress on stderr).
#
#   bash bench/llvmpipe/run.sh                 # the 18 standard rows: bunny, dragon, quad
#   FRAMES=11 bash bench/llvmpipe/run.sh       # quicker
#   ROUNDS=5 bash bench/llvmpipe/run.sh        # each row measured 5 times (default 3), median kept
#   MODELS=bunny,quad SIZES=1920x1080 bash bench/llvmpipe/run.sh
#   MODELS=sphere,teapot,bunny,dragon,quad bash bench/llvmpipe/run.sh   # with the small built-in models
#   MESA25=0 bash bench/llvmpipe/run.sh        # Debian's Mesa only (no download)
#   UPDATE=1 bash bench/llvmpipe/run.sh        # also rewrite BENCHMARKS.md's measured part
#
# Images (ours and llvmpipe's) are left in target/llvmpipe/.
set -euo pipefail
cd "$(dirname "$0")/../.."
out=target/llvmpipe
frames=${FRAMES:-31}

if ! dpkg-query -W -f='${Status}' libegl-mesa0 libgl1-mesa-dri 2>/dev/null | grep -q "ok installed"; then
  echo "installing Mesa (llvmpipe) ..." >&2
  apt-get update -qq >&2
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libegl-mesa0 libgl1-mesa-dri libegl1 libgbm1 >&2
fi
if ! python3 -c "import venv, ensurepip" 2>/dev/null; then
  apt-get update -qq >&2
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3-venv >&2
fi
if [ ! -x "$out/venv/bin/python" ]; then
  python3 -m venv "$out/venv" >&2
fi
"$out/venv/bin/pip" install -q moderngl numpy pillow >&2

mesa_env=()
if [ "${MESA25:-1}" != 0 ]; then
  mkdir -p "$out"
  bash bench/mesa/fetch.sh >"$out/mesa-25.env"
  mesa_env+=(--mesa-env "$out/mesa-25.env")
fi

cargo build --release --locked -q >&2
bin=${CARGO_TARGET_DIR:-target}/release/shadelab
select=(--model "${MODELS:-bunny,dragon,quad}")
[ -n "${SIZES:-}" ] && select+=(--size "$SIZES")
rm -rf "$out/scenes"
"$bin" bench --export "$out/scenes" "${select[@]}" >&2

LP_NUM_THREADS=2 "$out/venv/bin/python" bench/llvmpipe/compare.py \
  --scenes "$out/scenes" --shadelab "$bin" --images "$out/images" --frames "$frames" \
  --rounds "${ROUNDS:-3}" "${mesa_env[@]}" \
  --command "${FRAMES:+FRAMES=$FRAMES }${ROUNDS:+ROUNDS=$ROUNDS }${MODELS:+MODELS=$MODELS }${SIZES:+SIZES=$SIZES }${MESA25:+MESA25=$MESA25 }bash bench/llvmpipe/run.sh" \
  | tee "$out/report.md"

if [ -n "${UPDATE:-}" ]; then
  # Replace what lies between the two markers of BENCHMARKS.md.
  python3 - "$out/report.md" <<'PY'
import sys, pathlib
report = pathlib.Path(sys.argv[1]).read_text()
path = pathlib.Path("BENCHMARKS.md")
text = path.read_text()
begin, end = "<!-- measured: begin -->", "<!-- measured: end -->"
head, rest = text.split(begin, 1)
_, tail = rest.split(end, 1)
path.write_text(head + begin + "\n" + report.rstrip() + "\n" + end + tail)
print("BENCHMARKS.md updated", file=sys.stderr)
PY
fi
