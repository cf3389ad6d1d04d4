#!/usr/bin/env bash
# vmt golden as a test engineer meets it: baselines written, checked, a change caught with its
# page, JUnit and JSON for CI, masks, series and their contact sheet; and the ctest golden_<scene>
# layout (--no-run on an earlier run). Usage: golden_test.sh VMT SRC OUT
set -u
vmt=$1 src=$2 out=$3
rm -rf "$out" && mkdir -p "$out"
fails=0 passes=0
check() {  # check NAME EXPECTED_EXIT PATTERN -- command...
  local name=$1 want=$2 pattern=$3; shift 4
  local log="$out/$name.log"
  "$@" >"$log" 2>&1
  local got=$?
  if [ "$got" != "$want" ]; then
    echo "FAIL $name: exit $got, wanted $want"; sed 's/^/    /' "$log" | head -20; fails=$((fails+1)); return
  fi
  if [ -n "$pattern" ] && ! grep -qE -- "$pattern" "$log"; then
    echo "FAIL $name: output lacks /$pattern/"; sed 's/^/    /' "$log" | head -20; fails=$((fails+1)); return
  fi
  echo "ok   $name"; passes=$((passes+1))
}

check help 0 "--create-missing" -- "$vmt" golden check --help
check update_help 0 "--golden" -- "$vmt" golden update --help
check imgdiff_project_tolerance 0 "=0.0005" -- "$vmt" imgdiff --help

# A small scene: one picture at a time, a masked series of five.
cat >"$out/turn.yaml" <<EOT
scene: turn
model: $src/models/lathe-c1/machine.yaml
backend: kinematic
duration: 1.2
workpiece: {diameter: 60, length: 160, z: 60}
initial: {Z: 500, X: 200, T: 0, W: 300}
timeline:
  - move: {axis: Z, to: 300, feed: 18000}
snapshots:
  - {at: 0.5, camera: iso, width: 160, height: 120}
  - {every: 0.25, from: 0, to: 1, camera: work, width: 160, height: 120, file: "z-{i}.png",
     mask: [[0, 0, 20, 10]]}
EOT
g=$out/baselines r=$out/runs
check missing_fails 1 "FAIL turn/iso_0.5s.png: no golden .*vmt golden update" -- \
  "$vmt" golden check "$out/turn.yaml" --golden "$g" --out "$r"
check update 0 "golden: turn: 6 pictures, 0 failed" -- "$vmt" golden update "$out/turn.yaml" --golden "$g" --out "$r"
for f in iso_0.5s.png z-1.png z-2.png z-3.png z-4.png z-5.png; do
  check "update_wrote_$f" 0 "" -- cmp "$g/turn/$f" "$r/turn/$f"
done
check series_sheet 0 "" -- test -s "$r/turn/z-sheet.png"
check sheet_no_baseline 1 "" -- test -e "$g/turn/z-sheet.png"
check summary_lists_sheet 0 '"contact_sheets"' -- cat "$r/turn/summary.json"
check check_passes 0 "golden: turn: 6 pictures, 0 failed" -- \
  "$vmt" golden check "$out/turn.yaml" --golden "$g" --out "$r" --junit "$out/pass.xml" --json "$out/pass.json"
check check_masked 0 "ok   turn/z-1.png: equal \(0 pixels beyond tolerance 2, 200 masked\)" -- cat "$out/check_passes.log"
check junit_suite 0 '<testsuite name="turn" tests="7" failures="0"' -- cat "$out/pass.xml"
check junit_case 0 '<testcase classname="golden.turn" name="z-3.png">' -- cat "$out/pass.xml"
check json_passed 0 '"passed": true' -- cat "$out/pass.json"
check junit_well_formed 0 "" -- python3 -c "import sys, xml.dom.minidom as m; m.parse(sys.argv[1])" "$out/pass.xml"

# A tampered baseline fails with its figures, the three pictures and the page; a masked
# change passes.
cp "$g/turn/z-5.png" "$g/turn/z-1.png"
python3 - "$g/turn/z-2.png" <<'PY' || { echo "FAIL tamper: python3"; fails=$((fails+1)); }
import struct, sys, zlib
# Paints the masked corner (0, 0, 20, 10) black in a copy of the PNG (8-bit RGBA, as WritePng).
path = sys.argv[1]
data = open(path, 'rb').read()
w, h = struct.unpack('>II', data[16:24])
idat, pos = b'', 8
while pos < len(data):
    n, kind = struct.unpack('>I4s', data[pos:pos + 8])
    if kind == b'IDAT': idat += data[pos + 8:pos + 8 + n]
    pos += 12 + n
raw, rows, prev, stride = zlib.decompress(idat), [], bytearray(w * 4), w * 4
for y in range(h):
    f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for i in range(stride):
        a = line[i - 4] if i >= 4 else 0
        b, c = prev[i], (prev[i - 4] if i >= 4 else 0)
        p = a + b - c
        pred = a if abs(p - a) <= abs(p - b) and abs(p - a) <= abs(p - c) else (b if abs(p - b) <= abs(p - c) else c)
        line[i] = (line[i] + [0, a, b, (a + b) // 2, pred][f]) & 255
    rows.append(line); prev = line
for y in range(10):
    rows[y][0:20 * 4] = bytes([0, 0, 0, 255]) * 20
def chunk(kind, body):
    return struct.pack('>I', len(body)) + kind + body + struct.pack('>I', zlib.crc32(kind + body))
body = zlib.compress(b''.join(b'\0' + bytes(r) for r in rows))
open(path, 'wb').write(data[:8] + chunk(b'IHDR', data[16:29]) + chunk(b'IDAT', body) + chunk(b'IEND', b''))
PY
check tampered 1 "FAIL turn/z-1.png: different: [0-9]+ pixels \([0-9.]+ % of 19000 compared, allowed 0.0500 %\)" -- \
  "$vmt" golden check "$out/turn.yaml" --golden "$g" --out "$r" --junit "$out/fail.xml" --json "$out/fail.json"
check tampered_masked_passes 0 "ok   turn/z-2.png: equal" -- cat "$out/tampered.log"
fail=$r/golden-failures/turn/z-1
check tampered_prints_page 0 "page:   $fail/index.html" -- cat "$out/tampered.log"
check tampered_prints_replay 0 "replay: vmt view $r/turn --http 127.0.0.1:8080, then open http://127.0.0.1:8080/\?t=0" -- cat "$out/tampered.log"
check page_actual 0 "" -- cmp "$fail/actual.png" "$r/turn/z-1.png"
check page_golden 0 "" -- cmp "$fail/golden.png" "$g/turn/z-1.png"
check page_diff 0 "" -- test -s "$fail/diff.png"
check page_side_by_side 0 '<img src="golden.png">.*|<img src="actual.png">' -- cat "$fail/index.html"
check page_links_replay 0 'href="http://127.0.0.1:8080/\?t=0"' -- cat "$fail/index.html"
check page_only_failing 1 "" -- test -e "$r/golden-failures/turn/z-2"
check junit_failure 0 '<testsuite name="turn" tests="7" failures="1"' -- cat "$out/fail.xml"
check junit_failure_figures 0 '<failure message="different: [0-9]+ pixels.*type="failed">' -- cat "$out/fail.xml"
check json_failed 0 '"status": "failed"' -- cat "$out/fail.json"
check json_top_failed 0 '^  "passed": false' -- cat "$out/fail.json"
# Left-over baselines fail a check; update removes them and restores the tampered one.
cp "$g/turn/z-3.png" "$g/turn/old.png"
check left_over 1 "FAIL turn/old.png: golden not written by the scene" -- \
  "$vmt" golden check "$out/turn.yaml" --golden "$g" --out "$r"
check update_again 0 "del  turn/old.png" -- "$vmt" golden update "$out/turn.yaml" --golden "$g" --out "$r"
check restored 0 "golden: turn: 6 pictures, 0 failed" -- "$vmt" golden check "$out/turn.yaml" --golden "$g" --out "$r"
check failures_cleared 1 "" -- test -e "$r/golden-failures/turn"
rm "$g/turn/z-4.png"
check create_missing 0 "new  turn/z-4.png: baseline written" -- \
  "$vmt" golden check "$out/turn.yaml" --golden "$g" --out "$r" --create-missing
check created 0 "" -- test -s "$g/turn/z-4.png"

# A scene that fails its expectations: the check fails on its run; update writes nothing.
sed 's/^timeline:/expect:\n  - {axis: Z, position: 123, tol: 0.001}\ntimeline:/' "$out/turn.yaml" >"$out/failing.yaml"
check run_fails 1 "FAIL failing: " -- "$vmt" golden check "$out/failing.yaml" --golden "$g" --out "$r" --junit "$out/run.xml"
check run_fails_junit 0 '<testcase classname="golden.failing" name="run">' -- cat "$out/run.xml"
check update_failing_writes_none 1 "" -- "$vmt" golden update "$out/failing.yaml" --golden "$g" --out "$r"
check update_failing_nothing 1 "" -- test -e "$g/failing"
mkdir -p "$out/other" && cp "$out/turn.yaml" "$out/other/turn.yaml"
check same_name_twice 2 "a second scene named 'turn'" -- "$vmt" golden check "$out/turn.yaml" "$out/other/turn.yaml" --golden "$g"
mkdir -p "$r/golden-failures/turn/mine" && echo keep >"$r/golden-failures/turn/mine/notes.txt"
check fail_dir_keeps_others 0 "" -- sh -c "\"$vmt\" golden check \"$out/turn.yaml\" --golden \"$g\" --out \"$r\" >/dev/null && test -s \"$r/golden-failures/turn/mine/notes.txt\""
check bad_scene 2 "nope.yaml" -- "$vmt" golden check "$out/nope.yaml" --golden "$g"
# ... and the other scenes are still checked and reported.
check bad_scene_others 2 "golden: turn: 6 pictures, 0 failed" -- \
  "$vmt" golden check "$out/nope.yaml" "$out/turn.yaml" --golden "$g" --out "$r" --junit "$out/bad.xml"
check bad_scene_junit 0 '<testsuite name="nope" tests="1" failures="1"' -- cat "$out/bad.xml"
sed 's/mask: \[\[0, 0, 20, 10\]\]/mask: [[150, 0, 20, 10]]/' "$out/turn.yaml" >"$out/bad_mask.yaml"
check bad_mask 2 "bad_mask.yaml:[0-9]+:[0-9]+: snapshots\[1\]\.mask\[0\]: reaches beyond the 160x120 picture" -- \
  "$vmt" golden check "$out/bad_mask.yaml" --golden "$g"

# As ctest's golden_<scene> tests run it: --no-run on the folder of an earlier vmt run (the
# scene test's), baselines in DIR/<scene>/.
"$vmt" run "$out/turn.yaml" --out "$out/scenes/turn" >"$out/turn_run.log" 2>&1
ctest_check() {  # ctest_check BASELINES FAIL_DIR [RUNS]
  "$vmt" golden check "$out/turn.yaml" --no-run --golden "$1" --out "${3:-$out/scenes}" --fail-dir "$2"
}
mkdir -p "$out/same/turn" "$out/changed/turn" "$out/extra/turn"
cp "$out/scenes/turn/"*.png "$out/same/turn/" && rm "$out/same/turn/z-sheet.png"
check no_run_same 0 "golden: turn: 6 pictures, 0 failed" -- ctest_check "$out/same" "$out/fail_same"
check no_run_same_leaves_nothing 1 "" -- test -e "$out/fail_same/turn"
cp "$out/same/turn/"*.png "$out/changed/turn/"
cp "$out/scenes/turn/z-5.png" "$out/changed/turn/iso_0.5s.png"  # another picture in its place
check no_run_changed 1 "FAIL turn/iso_0.5s.png: different: [0-9]+ pixels" -- ctest_check "$out/changed" "$out/fail"
check no_run_changed_page 0 'href="http://127.0.0.1:8080/\?t=0.5' -- cat "$out/fail/turn/iso_0.5s/index.html"
check no_run_changed_others_passed 1 "" -- test -e "$out/fail/turn/z-1"
cp "$out/same/turn/"*.png "$out/extra/turn/"
"$vmt" snapshot "$out/turn.yaml" --at 0.5 --camera iso --width 80 --height 60 --out "$out/extra/turn/iso_0.5s.png" >/dev/null
check no_run_size 1 "FAIL turn/iso_0.5s.png: different sizes: 80x60 vs 160x120" -- ctest_check "$out/extra" "$out/fail_size"
check no_run_no_run 1 "events.jsonl is missing" -- ctest_check "$out/same" "$out/fail_no_run" "$out/nothing"

echo "golden: $passes passed, $fails failed"
[ "$fails" -eq 0 ]
