#!/usr/bin/env bash
# The viewer's workload (480x480, each method, one thread) in WebAssembly
# under Node, with the portable lanes against the best level of the module:
# built without and with simd128 (where the best is the simd128 backend).
#   bash bench/wasm/run.sh [model.obj...]   (default: the teapot, the bunny and the dragon)
set -euo pipefail
cd "$(dirname "$0")"
rustup target add wasm32-unknown-unknown >/dev/null 2>&1 || true
models=("$@")
if [ ${#models[@]} -eq 0 ]; then
  models=(teapot)
  for m in stanford-bunny.obj dragon_100k.obj; do
    [ -f "../../../shared/models/$m" ] && models+=("../../../shared/models/$m")
  done
fi
for flavour in portable simd128; do
  flags=""
  [ "$flavour" = simd128 ] && flags="-C target-feature=+simd128"
  RUSTFLAGS="$flags" CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-target}/$flavour" cargo build -q --release --target wasm32-unknown-unknown
  echo "== built $flavour"
  node run.js "${CARGO_TARGET_DIR:-target}/$flavour/wasm32-unknown-unknown/release/shadelab_wasm_bench.wasm" "${SIZE:-480x480}" "${FRAMES:-30}" "${models[@]}"
done
