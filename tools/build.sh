#!/usr/bin/env bash
# Set up (Debian packages), configure and build into build/: everything, or only the targets
# named (tools/demo.sh builds `vmt` alone). Warnings are errors under CI.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup-debian.sh
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DVMT_WERROR=$werror >/dev/null
cmake --build build ${1:+--target "$@"}
