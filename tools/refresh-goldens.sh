#!/usr/bin/env bash
# Rewrites the golden images (tests/golden/<scene>/) from the scenes' snapshots after an
# intended change of the pictures: a model, a camera, a scene or the renderer changed.
# Usage: tools/refresh-goldens.sh [BUILD_DIR] [SCENE...]
#   BUILD_DIR  a built tree (default: build); its sim/vmt renders
#   SCENE      scene names (turning, repos-collision, ...); default: every showcase scene, i.e.
#              every scenes/*.yaml but the fault-* ones (tests/CMakeLists.txt tests the same)
# A scene that fails its expectations is not refreshed (its pictures would not be the scene's).
# Look at the pictures (git diff --stat tests/golden; an image viewer) before committing them.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
[ $# -gt 0 ] && shift
vmt=$build/sim/vmt
[ -x "$vmt" ] || { echo "no $vmt: build first (cmake --build $build --target vmt)"; exit 2; }
export GALLIUM_DRIVER=llvmpipe  # the goldens are llvmpipe's pictures (DESIGN.md)

if [ $# -gt 0 ]; then
  names=("$@")
else
  names=()
  for f in "$root"/scenes/*.yaml; do
    n=$(basename "$f" .yaml)
    [[ $n == fault-* ]] || names+=("$n")
  done
fi

failed=0
for name in "${names[@]}"; do
  out=$build/test_output/refresh-goldens/$name
  rm -rf "$out" && mkdir -p "$out"
  if ! "$vmt" run "$root/scenes/$name.yaml" --out "$out" >"$out.log" 2>&1; then
    echo "FAIL $name: the scene failed, goldens kept (see $out.log)"
    failed=$((failed + 1))
    continue
  fi
  golden=$root/tests/golden/$name
  rm -rf "$golden" && mkdir -p "$golden"
  count=0
  while read -r shot; do
    cp "$out/$shot" "$golden/$shot"
    count=$((count + 1))
  done < <(grep '"event":"snapshot"' "$out/events.jsonl" | grep -o '"file":"[^"]*"' | cut -d'"' -f4)
  echo "ok   $name: $count pictures"
done
[ "$failed" -eq 0 ]
