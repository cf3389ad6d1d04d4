#!/usr/bin/env bash
# Rewrites what tests/golden/<scene>/ pins after an intended change of behaviour or pictures:
#   digest  the trace digest per backend: the scene's own, and the other backend's where the
#           scene passes its expectations there too (tests/golden/run_scene.sh checks them)
#   *.png   the golden images of a showcase scene (every scene but the fault-* ones)
# Usage: tools/refresh-goldens.sh [BUILD_DIR] [SCENE...]
#   BUILD_DIR  a built tree (default: build); its sim/vmt runs the scenes. A sanitizer build
#              (build-asan) only writes "BACKEND asan DIGEST" lines, and only where its bytes
#              differ from the release build's (they do not today: docs/architecture.md, Determinism)
#   SCENE      scene names (turning, repos-collision, ...); default: every scenes/*.yaml
# A scene that fails its expectations is not refreshed. Look at the pictures (git diff --stat
# tests/golden; an image viewer) and say in the commit why the behaviour changed.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
[ $# -gt 0 ] && shift
vmt=$build/sim/vmt
[ -x "$vmt" ] || { echo "no $vmt: build first (cmake --build $build --target vmt)"; exit 2; }
export GALLIUM_DRIVER=llvmpipe  # the goldens are llvmpipe's pictures (docs/architecture.md, Determinism)
kind=release
grep -q '^CMAKE_CXX_FLAGS:.*sanitize' "$build/CMakeCache.txt" 2>/dev/null && kind=asan

if [ $# -gt 0 ]; then
  names=("$@")
else
  names=()
  for f in "$root"/scenes/*.yaml; do names+=("$(basename "$f" .yaml)"); done
fi

digest_of() { grep -o '"trace_digest": *"[0-9a-f]*"' "$1/summary.json" | cut -d'"' -f4; }

failed=0
for name in "${names[@]}"; do
  scene=$root/scenes/$name.yaml
  out=$build/test_output/refresh-goldens/$name
  rm -rf "$out" "$out"_other && mkdir -p "$out"
  if ! "$vmt" run "$scene" --out "$out" >"$out.log" 2>&1; then
    echo "FAIL $name: the scene failed, goldens kept (see $out.log)"
    failed=$((failed + 1))
    continue
  fi
  golden=$root/tests/golden/$name
  mkdir -p "$golden"
  own=$(grep -o '^backend: *[a-z]*' "$scene" | awk '{print $2}')
  other=physics
  [ "$own" = physics ] && other=kinematic
  declare -A digest=([$own]=$(digest_of "$out"))
  if "$vmt" run "$scene" --backend "$other" --out "$out"_other >"$out"_other.log 2>&1; then
    digest[$other]=$(digest_of "$out"_other)
  fi

  file=$golden/digest
  old=$(cat "$file" 2>/dev/null || true)
  {
    echo "# The trace digest of this scene per backend (tests/golden/run_scene.sh; written by"
    echo "# tools/refresh-goldens.sh). A change is a change of the scene's behaviour."
    for b in physics kinematic; do
      general=$(awk -v b="$b" '$1 == b && NF == 2 { print $2 }' <<<"$old")
      [ "$kind" = release ] && general=${digest[$b]:-}
      [ -n "$general" ] && echo "$b $general"
      if [ "$kind" = release ]; then  # a sanitizer build's own line is the sanitizer build's
        awk -v b="$b" '$1 == b && NF == 3' <<<"$old"
      elif [ -n "${digest[$b]:-}" ] && [ "${digest[$b]}" != "$general" ]; then
        echo "$b asan ${digest[$b]}"
      fi
    done
  } >"$file"
  unset digest

  count=0
  if [[ $name != fault-* ]]; then
    # The pictures of the run above as the baselines (pictures no snapshot writes any more go).
    "$vmt" golden update "$scene" --no-run --golden "$root/tests/golden" \
      --out "$build/test_output/refresh-goldens" >"$out.golden.log" 2>&1 ||
      { echo "FAIL $name: vmt golden update (see $out.golden.log)"; failed=$((failed + 1)); }
    count=$(grep -c '^\(new\|upd\) ' "$out.golden.log")
  fi
  echo "ok   $name: $(grep -c '^[a-z]' "$file") digests, $count pictures"
done
[ "$failed" -eq 0 ]
