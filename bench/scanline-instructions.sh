#!/usr/bin/env bash
# Instructions executed by scanline renders of each method, counted by
# callgrind (deterministic, unlike wall-clock time on a shared machine).
# Compare two builds side by side, e.g. before and after a change:
#   bench/scanline-instructions.sh /tmp/before/shadelab target/release/shadelab
# Extra arguments after `--` go to `shadelab render`.
set -euo pipefail
binaries=()
while [[ $# -gt 0 && $1 != -- ]]; do binaries+=("$1"); shift; done
[[ ${1:-} == -- ]] && shift
extra=("$@")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf '%-10s' method
for b in "${binaries[@]}"; do printf ' %22s' "$(basename "$(dirname "$b")")/$(basename "$b")"; done
echo
for shading in flat gouraud phong; do
  printf '%-10s' "$shading"
  for b in "${binaries[@]}"; do
    valgrind --tool=callgrind --callgrind-out-file="$out/cg" \
      "$b" render --model teapot --detail 12 --size 800x600 --rasterizer scanline \
      --shading "$shading" -o "$out/x.png" "${extra[@]}" >/dev/null 2>"$out/log"
    printf ' %22s' "$(grep -o 'Collected : [0-9]*' "$out/log" | grep -o '[0-9]*$')"
  done
  echo
done
