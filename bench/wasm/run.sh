#!/usr/bin/env bash
# The viewer's workload (teapot, 480x480, each method, one thread) in
# WebAssembly under Node, with the portable lanes and with simd128.
set -euo pipefail
cd "$(dirname "$0")"
rustup target add wasm32-unknown-unknown >/dev/null 2>&1 || true
for flavour in portable simd128; do
  flags=""
  [ "$flavour" = simd128 ] && flags="-C target-feature=+simd128"
  RUSTFLAGS="$flags" CARGO_TARGET_DIR="target/$flavour" cargo build -q --release --target wasm32-unknown-unknown
  echo "== $flavour"
  node run.js "target/$flavour/wasm32-unknown-unknown/release/shadelab_wasm_bench.wasm" "${SIZE:-480x480}" "${FRAMES:-60}"
done
