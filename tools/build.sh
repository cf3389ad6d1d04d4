#!/usr/bin/env bash
# Set up (Debian packages), configure and build vmt into build/. Warnings are errors under CI.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup-debian.sh
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DVMT_WERROR=$werror >/dev/null
cmake --build build
