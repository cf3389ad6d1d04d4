#!/usr/bin/env bash
# The REPOS study showcase from scratch with two worker processes: writes out/bench/study.json
# ({"cases_per_minute": N, ...}) and leaves the study in out/bench/study/. Build first.
set -euo pipefail
cd "$(dirname "$0")/.."
vmt=${VMT:-build/sim/vmt}
mkdir -p out/bench
rm -rf out/bench/study
"$vmt" study repos scenes/study-repos-turning.yaml --out out/bench/study --jobs "${JOBS:-2}" \
  --bench-json out/bench/study.json
cat out/bench/study.json
