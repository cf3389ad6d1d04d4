#!/usr/bin/env bash
# A scene's pictures against its golden images (image regression).
# Usage: check_scene.sh VMT GOLDEN_DIR SCENE_OUT FAIL_DIR
#   GOLDEN_DIR  tests/golden/<scene>: the golden pictures, named as the scene names its snapshots
#   SCENE_OUT   the scene's `vmt run --out` folder (the scene test's, so the scene runs once)
#   FAIL_DIR    where a failing picture leaves <picture>/actual.png, diff.png, golden.png and
#               index.html: the three side by side, and how to watch the run at its time
# Every snapshot the scene wrote (its `snapshot` events) must have a golden of the same name
# and match it; every golden must have been written, so that a renamed or dropped snapshot
# shows. Exit 0 all match, 1 otherwise. Refresh after an intended change:
# tools/refresh-goldens.sh BUILD_DIR [SCENE...].
set -u
vmt=$1 golden=$2 run=$3 fail=$4

# llvmpipe renders the same bytes on one machine (any LP_NUM_THREADS, tests/cli/cli_test.sh; the
# same with LP_NATIVE_VECTOR_WIDTH=128), so here the pictures are equal. Another CPU may get
# other shader code from llvmpipe: with none of SSE/AVX (GALLIUM_NOSSE=1, the far end of that)
# the goldens differed in at most 0.021 % of their pixels (edge pixels, up to 91 levels; 2 levels
# per channel change little), measured 2026-11-24 on default, measure-shaft, repos-collision,
# measure-move-collision, block-search-refused and more. A difference in at most 0.05 % of the
# pixels (38 at 320x240) beyond 2 levels passes: 2.4 times that, and half of what a turret
# detail added since the first golden of `default` changed in its work picture (0.10 %).
tolerance=2 allowed_fraction=0.0005

# A failing picture's page: golden, actual and difference side by side, and the link that opens
# the run's replay (vmt view) at the picture's time.
write_failure_page() {  # write_failure_page DIR SHOT WHAT REPLAY_COMMAND T
  local dir=$1 shot=$2 what=$3 replay=$4 t=$5
  local diff_img=""
  [ -f "$dir/diff.png" ] && diff_img='<figure><img src="diff.png"><figcaption>difference</figcaption></figure>'
  cat > "$dir/index.html" <<HTML
<!DOCTYPE html><html><head><meta charset="utf-8"><title>$shot differs from its golden</title>
<style>body{font-family:sans-serif;margin:2em}figure{display:inline-block;margin:4px}</style></head>
<body><h1>$shot differs from its golden</h1><p>$what</p>
<figure><img src="golden.png"><figcaption>golden</figcaption></figure>
<figure><img src="actual.png"><figcaption>actual</figcaption></figure>$diff_img
<p>Watch the run at the picture's time (t = $t s): run <code>$replay</code>, then open
<a href="http://127.0.0.1:8080/?t=$t">http://127.0.0.1:8080/?t=$t</a>.</p></body></html>
HTML
}

rm -rf "$fail"
events=$run/events.jsonl
if [ ! -f "$events" ]; then
  echo "FAIL: $events is missing: the scene did not run"
  exit 1
fi
mapfile -t shots < <(grep '"event":"snapshot"' "$events" | grep -o '"file":"[^"]*"' | cut -d'"' -f4)
if [ "${#shots[@]}" -eq 0 ]; then
  echo "FAIL: the scene writes no snapshot; a showcase scene needs one (docs/scene-format.md)"
  exit 1
fi

fails=0
for shot in "${shots[@]}"; do
  if [ ! -f "$golden/$shot" ]; then
    echo "FAIL $shot: no golden $golden/$shot (new snapshot? tools/refresh-goldens.sh)"
    fails=$((fails + 1))
    continue
  fi
  where=$fail/${shot%.png}
  mkdir -p "$where"
  if out=$("$vmt" imgdiff "$golden/$shot" "$run/$shot" --tolerance "$tolerance" \
             --allowed-fraction "$allowed_fraction" --diff "$where/diff.png" 2>&1); then
    echo "ok   $shot: $out"
    rmdir "$where"
    continue
  fi
  cp "$run/$shot" "$where/actual.png"
  cp "$golden/$shot" "$where/golden.png"
  # The picture's time, to watch the run there in the operator station.
  t=$(grep '"event":"snapshot"' "$events" | grep -F "\"file\":\"$shot\"" | head -1 |
      sed -n 's/^{"t":\([0-9.e+-]*\),.*/\1/p')
  replay="vmt view $(cd "$run" && pwd) --http 127.0.0.1:8080"
  write_failure_page "$where" "$shot" "$out" "$replay" "${t:-0}"
  echo "FAIL $shot: $out"
  echo "     golden: $golden/$shot"
  echo "     actual: $where/actual.png"
  [ -f "$where/diff.png" ] && echo "     diff:   $where/diff.png"
  echo "     page:   $where/index.html (the three side by side)"
  echo "     replay: $replay, then open http://127.0.0.1:8080/?t=${t:-0}"
  fails=$((fails + 1))
done
for g in "$golden"/*.png; do
  [ -e "$g" ] || continue
  name=$(basename "$g")
  if ! printf '%s\n' "${shots[@]}" | grep -qxF "$name"; then
    echo "FAIL $name: golden not written by the scene (snapshot renamed or dropped? tools/refresh-goldens.sh)"
    fails=$((fails + 1))
  fi
done
rmdir "$fail" 2>/dev/null
echo "golden: ${#shots[@]} pictures, $fails failed (tolerance $tolerance, allowed fraction $allowed_fraction)"
[ "$fails" -eq 0 ]
