#!/usr/bin/env bash
# A scene test: runs the scene and checks its trace digest against the pinned one.
# Usage: run_scene.sh VMT SCENE_YAML OUT DIGEST_FILE BUILD_KIND [BACKEND]
#   DIGEST_FILE  tests/golden/<scene>/digest: one line per backend, "BACKEND DIGEST", or
#                "BACKEND BUILD_KIND DIGEST" where a build kind gives other bytes (none does
#                today: see docs/architecture.md, Determinism)
#   BUILD_KIND   release or asan (the sanitizer build)
#   BACKEND      physics or kinematic; default the scene's own
# The trace is a pure function of the scene: any change of its digest is a change of behaviour,
# intended or not. After an intended one: tools/refresh-goldens.sh BUILD_DIR SCENE, and say in the
# commit why the scene's behaviour changed.
set -u
vmt=$1 scene=$2 out=$3 digests=$4 kind=$5 backend=${6:-}

args=(run "$scene" --out "$out")
[ -n "$backend" ] && args+=(--backend "$backend")
"$vmt" "${args[@]}" || exit 1

summary=$out/summary.json
digest=$(grep -o '"trace_digest": *"[0-9a-f]*"' "$summary" | cut -d'"' -f4)
ran_on=$(grep -o '"backend": *"[a-z]*"' "$summary" | cut -d'"' -f4)
if [ -z "$digest" ] || [ -z "$ran_on" ]; then
  echo "FAIL: $summary names no trace digest or backend"
  exit 1
fi
if [ ! -f "$digests" ]; then
  echo "FAIL: no pinned digest $digests (new scene? tools/refresh-goldens.sh)"
  exit 1
fi
# A line for this build kind wins over the line for every build.
pinned=$(awk -v b="$ran_on" -v k="$kind" '
  $1 == b && NF == 3 && $2 == k { exact = $3 }
  $1 == b && NF == 2 { any = $2 }
  END { print (exact != "" ? exact : any) }' "$digests")
if [ -z "$pinned" ]; then
  echo "FAIL: $digests pins no digest for the $ran_on backend"
  exit 1
fi
if [ "$digest" != "$pinned" ]; then
  echo "FAIL: trace digest $digest on $ran_on ($kind build), pinned $pinned in $digests:"
  echo "      the scene's behaviour changed. If intended: tools/refresh-goldens.sh BUILD_DIR $(basename "$scene" .yaml)"
  exit 1
fi
echo "digest: $digest on $ran_on, as pinned"
