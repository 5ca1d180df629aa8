#!/usr/bin/env bash
# Where the viewer's WebAssembly engine spends a frame: the viewer's module
# (crates/shadelab-wasm, the `wasm` profile) built with its function names
# kept, then one part of the three methods at once (as a panel worker draws
# it) rendered FRAMES times under Node's sampling profiler, and the samples
# summed per function.
#   bash bench/wasm/profile.sh MODEL.obj [PART]   (PART of 2: 0 the top half, 1 the bottom; default 1)
# FRAMES (200), INTERVAL (sampling period in µs, 100). The module goes to
# target/wasm-profile (outside the viewer's own build, which strips names);
# the profile itself to target/wasm-profile/cpu/. Function-level only: for
# instructions, `perf record` of `node --perf-prof --no-liftoff` and
# `perf inject --jit` show V8's machine code with its samples.
set -euo pipefail
cd "$(dirname "$0")/../.."
model=${1:?usage: bash bench/wasm/profile.sh MODEL.obj [PART]}
part=${2:-1}
rustup target add wasm32-unknown-unknown >/dev/null 2>&1 || true
target=target/wasm-profile
CARGO_PROFILE_WASM_STRIP=none CARGO_ENCODED_RUSTFLAGS="-Ctarget-feature=+simd128" \
  cargo build -q --locked -p shadelab-wasm --profile wasm --target wasm32-unknown-unknown --target-dir "$target"
module="$target/wasm32-unknown-unknown/wasm/shadelab_wasm.wasm"
rm -rf "$target/cpu"
node --cpu-prof --cpu-prof-dir="$target/cpu" --cpu-prof-interval "${INTERVAL:-100}" \
  bench/wasm/part.mjs "$module" "$model" "$part" "${FRAMES:-200}"
python3 bench/wasm/cpuprofile.py "$target"/cpu/*.cpuprofile
