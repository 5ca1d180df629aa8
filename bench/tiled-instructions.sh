#!/usr/bin/env bash
# Instructions per frame of the tiled rasterizer on standard-scene rows,
# counted by callgrind on one thread (deterministic, unlike wall-clock time
# on a shared machine), split into the geometry stage (vertices, setup,
# binning) and the bands (walk, shade, write-out).
#
#   bench/tiled-instructions.sh [BINARY]            # the rows below
#   ROWS="bunny:512x512:phong quad:1920x1080:flat" bench/tiled-instructions.sh
#
# Each row is measured as the difference of two runs (1 warm-up + 1 frame,
# and 1 warm-up + 3 frames) divided by 2: the steady-state frame, without
# loading, once-per-mesh work or the first frame's allocations.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-target/release/shadelab}
models=${MODELS_DIR:-../shared/models}
rows=${ROWS:-"bunny:512x512:flat bunny:512x512:gouraud bunny:512x512:phong
bunny:1920x1080:flat bunny:1920x1080:gouraud bunny:1920x1080:phong
dragon:512x512:flat dragon:512x512:gouraud dragon:512x512:phong
dragon:1920x1080:flat dragon:1920x1080:gouraud dragon:1920x1080:phong
quad:1920x1080:flat quad:1920x1080:gouraud quad:1920x1080:phong"}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# Inclusive instructions of the renderer and of its geometry stage.
count() {
  local frames=$1 model=$2 size=$3 shading=$4
  valgrind --tool=callgrind --callgrind-out-file="$out/cg" \
    --toggle-collect='*Renderer*render_into*' \
    "$bin" bench --threads 1 --warmup 1 --frames "$frames" --rasterizer tiled \
    --model "$model" --size "$size" --shading "$shading" --models-dir "$models" \
    >/dev/null 2>"$out/log"
  local total geometry
  total=$(grep -o 'Collected : [0-9]*' "$out/log" | grep -o '[0-9]*$')
  geometry=$(callgrind_annotate --inclusive=yes --threshold=100 "$out/cg" 2>/dev/null |
    grep 'TiledRasterizer::geometry \[' | head -1 | awk '{gsub(",", "", $1); print $1}' || true)
  echo "$total ${geometry:-0}"
}

printf '%-8s %-10s %-8s %12s %12s %12s %10s\n' model size shading 'M instr' geometry bands 'per pixel'
for row in $rows; do
  IFS=: read -r model size shading <<<"$row"
  read -r t1 g1 < <(count 1 "$model" "$size" "$shading")
  read -r t3 g3 < <(count 3 "$model" "$size" "$shading")
  w=${size%x*} h=${size#*x}
  awk -v m="$model" -v s="$size" -v sh="$shading" -v t1="$t1" -v t3="$t3" \
    -v g1="$g1" -v g3="$g3" -v px=$((w * h)) 'BEGIN {
      t = (t3 - t1) / 2; g = (g3 - g1) / 2;
      printf "%-8s %-10s %-8s %12.2f %12.2f %12.2f %10.2f\n", m, s, sh, t / 1e6, g / 1e6, (t - g) / 1e6, t / px
    }'
done
