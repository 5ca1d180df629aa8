#!/usr/bin/env bash
# The viewer's input-to-pixels latency (run.js), after `cargo build --release`:
#   bash bench/viewer/run.sh [--bin LABEL=PATH]... [--models teapot,bunny,dragon] [--rounds N] [--steps N]
# Installs playwright-core here (npm ci) and Debian's chromium when missing.
set -euo pipefail
cd "$(dirname "$0")"
if ! command -v chromium >/dev/null 2>&1; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq chromium >/dev/null
fi
[ -d node_modules/playwright-core ] || npm ci --no-audit --no-fund
exec node run.js "$@"
