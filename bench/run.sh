#!/usr/bin/env bash
# Runs every benchmark and writes its JSON to out/bench/<name>.json. Build first (tools/build.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
export GALLIUM_DRIVER=llvmpipe
mkdir -p out/bench
for b in backend_bench snapshot_bench render_bench axis_chain_eval nc_decode_bench block_search_bench \
  modbus_bench \
  path_guard_bench; do
  [ -x "build/bench/$b" ] || continue
  echo "== $b"
  "build/bench/$b" --benchmark_format=json --benchmark_out="out/bench/$b.json" \
    --benchmark_out_format=json --benchmark_format=console
done
# Real-time pacing of vmt serve: how late the PLC cycles start against the wall clock.
if [ -x build/sim/vmt ]; then
  echo "== serve --realtime"
  build/sim/vmt serve scenes/repos-machine-keys.yaml --modbus 127.0.0.1:0 --realtime \
    --out out/bench/serve_realtime >/dev/null 2>&1 || true
  cp out/bench/serve_realtime/serve.json out/bench/serve_realtime.json
  grep -A4 cycle_lateness out/bench/serve_realtime.json
fi

