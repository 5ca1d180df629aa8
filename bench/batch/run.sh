#!/usr/bin/env bash
# `shadelab batch` against pyrender (EGL) and Open3D on llvmpipe: 200 real
# meshes, 512×512 Phong, 6 views, images per second, on Debian's Mesa 22 and
# on Mesa 25.0.7 (bench/mesa/fetch.sh), in alternating rounds.
#
#   bash bench/batch/run.sh                  # 3 rounds, prints the markdown table
#   ROUNDS=5 bash bench/batch/run.sh
#   COUNT=50 ROUNDS=1 bash bench/batch/run.sh   # a quick look
#   OPEN3D=1 bash bench/batch/run.sh         # also try Open3D's OffscreenRenderer
#
# Open3D is off by default: its 0.20 wheel renders headless only through
# Filament's Vulkan backend (Mesa's lavapipe here), and there it hung on the
# first frame for 5 minutes (see BENCHMARKS.md).
#
# Makes everything it needs under target/bench-batch/ (a venv with pyrender,
# Open3D, trimesh, fast-simplification and the shadelab package; the
# decimated meshes, made from ../shared/models; Mesa 25 under target/mesa-25).
# Nothing it makes is committed.
set -euo pipefail
cd "$(dirname "$0")/../.."
work=target/bench-batch
models=${MODELS_DIR:-../shared/models}
[ -d "$models" ] || models=/work/shared/models
mkdir -p "$work"

if ! dpkg-query -W -f='${Status}' libegl-mesa0 libgl1-mesa-dri libegl1 2>/dev/null | grep -q "ok installed"; then
  apt-get update -qq >&2
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libegl-mesa0 libgl1-mesa-dri libegl1 libgbm1 libopengl0 >&2
fi
if [ "${OPEN3D:-0}" = 1 ] && ! dpkg-query -W -f='${Status}' libvulkan1 mesa-vulkan-drivers 2>/dev/null | grep -q "ok installed"; then
  # Open3D's renderer (Filament) draws through Vulkan when headless: Mesa's lavapipe.
  apt-get update -qq >&2
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libvulkan1 mesa-vulkan-drivers >&2
fi
venv=$work/venv
[ -x "$venv/bin/python" ] || python3 -m venv "$venv" >&2
"$venv/bin/pip" install -q -U pip >&2
# pyrender 0.1.45 pins PyOpenGL 3.1.0, whose EGL support predates Python 3.11; 3.1.10 works.
"$venv/bin/pip" install -q pyrender==0.1.45 trimesh "networkx>=3" "pyglet<2" fast-simplification pillow >&2
"$venv/bin/pip" install -q --no-deps PyOpenGL==3.1.10 >&2
if [ "${OPEN3D:-0}" = 1 ]; then "$venv/bin/pip" install -q open3d >&2; fi
"$venv/bin/pip" install -q ./crates/shadelab-py >&2

cargo build --release --locked -q >&2
"$venv/bin/python" bench/batch/make_meshes.py "$models" "$work" "${COUNT:-200}" >&2
mesa25=$(bash bench/mesa/fetch.sh)

"$venv/bin/python" bench/batch/bench.py \
  --manifest "$work/manifest.jsonl" --work "$work" --shadelab target/release/shadelab \
  --rounds "${ROUNDS:-3}" --views "${VIEWS:-6}" --size "${SIZE:-512}" \
  --mesa25 "$mesa25" --open3d "${OPEN3D:-0}" \
  --command "${ROUNDS:+ROUNDS=$ROUNDS }${COUNT:+COUNT=$COUNT }${OPEN3D:+OPEN3D=$OPEN3D }bash bench/batch/run.sh"
