#!/usr/bin/env bash
# Quick start 1: set up, build the `vmt` program alone (the tests are tools/test.sh's), and run
# the default scene: the lathe under its PLC turns a shaft, the operator interrupts it, jogs
# away and repositions through the program's REPOS subroutine. Results under out/default/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/build.sh vmt
export GALLIUM_DRIVER=llvmpipe
./build/sim/vmt run scenes/default.yaml --out out/default
