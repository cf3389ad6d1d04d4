#!/usr/bin/env bash
# Runs every benchmark, writes its JSON to out/bench/<name>.json, then the report of them all
# (out/bench/report.{json,md}). Build first (tools/build.sh); VMT_BUILD_DIR names another build
# folder (default build). Numbers on a machine that builds at the same time are disturbed.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${VMT_BUILD_DIR:-build}
export GALLIUM_DRIVER=llvmpipe
mkdir -p out/bench
for b in backend_bench snapshot_bench render_bench axis_chain_eval nc_decode_bench block_search_bench \
  modbus_bench \
  path_guard_bench trace_write_bench whole_run_bench; do
  [ -x "$build/bench/$b" ] || continue
  echo "== $b"
  "$build/bench/$b" --benchmark_format=json --benchmark_out="out/bench/$b.json" \
    --benchmark_out_format=json --benchmark_format=console
done
# Real-time pacing of vmt serve: how late the PLC cycles start against the wall clock.
if [ -x "$build/sim/vmt" ]; then
  echo "== serve --realtime"
  "$build/sim/vmt" serve scenes/repos-machine-keys.yaml --modbus 127.0.0.1:0 --realtime --no-wait-for-plc \
    --out out/bench/serve_realtime >/dev/null 2>&1 || true
  if [ -f out/bench/serve_realtime/serve.json ]; then
    cp out/bench/serve_realtime/serve.json out/bench/serve_realtime.json
    grep -A4 cycle_lateness out/bench/serve_realtime.json
  fi
fi
# vmt against LinuxCNC's interpreter where linuxcnc-uspace is installed (says so and goes on
# where it is not).
if [ -x "$build/bench/search_program" ] && [ -x "$build/sim/vmt" ]; then
  echo "== LinuxCNC comparison"
  python3 bench/linuxcnc_compare.py --build "$build" --out out/bench || true
fi
# Study cases per minute: the REPOS study showcase with two workers (out/bench/study.json).
if [ -x "$build/sim/vmt" ]; then
  echo "== study"
  VMT="$build/sim/vmt" bash bench/study.sh || true
fi
echo "== report"
python3 bench/report.py out/bench
cat out/bench/report.md
