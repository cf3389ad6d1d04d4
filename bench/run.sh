#!/usr/bin/env bash
# Runs every benchmark and writes its JSON to out/bench/<name>.json. Build first (tools/build.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
export GALLIUM_DRIVER=llvmpipe
mkdir -p out/bench
for b in backend_bench snapshot_bench render_bench axis_chain_eval nc_decode_bench; do
  [ -x "build/bench/$b" ] || continue
  echo "== $b"
  "build/bench/$b" --benchmark_format=json --benchmark_out="out/bench/$b.json" \
    --benchmark_out_format=json --benchmark_format=console
done
