#!/usr/bin/env bash
# The vmt command as a user meets it: exit codes, messages, files. Usage: cli_test.sh VMT SRC OUT
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

check help 0 "run.*snapshot.*imgdiff|Subcommands" -- "$vmt" --help
check run_help 0 "--backend" -- "$vmt" run --help
check snapshot_help 0 "--camera" -- "$vmt" snapshot --help
check imgdiff_help 0 "--diff" -- "$vmt" imgdiff --help
check no_subcommand 2 "" -- "$vmt"
check help_example 0 "Example:" -- "$vmt" study repos --help
check typo_run 2 "unknown command 'rn'; did you mean 'run'" -- "$vmt" rn
check typo_signals 2 "did you mean 'signals'" -- "$vmt" sigs
check typo_study 2 "vmt study: error: unknown command 'rpos'; did you mean 'repos'" -- "$vmt" study rpos
check typo_golden 2 "did you mean 'check'" -- "$vmt" golden chek
check not_a_command 2 "unknown command 'scene.yaml'" -- "$vmt" scene.yaml
check unknown_option 2 "" -- "$vmt" run "$src/scenes/drive-timeline.yaml" --bogus

check run_kinematic 0 "10 passed, 0 failed" -- "$vmt" run "$src/scenes/drive-timeline.yaml" --backend kinematic --out "$out/run"
for f in trace.csv events.jsonl summary.json iso_3.2s.png work_3.2s.png; do
  check "run_wrote_$f" 0 "" -- test -s "$out/run/$f"
done
check summary_has_digest 0 '"trace_digest": "[0-9a-f]{16}"' -- cat "$out/run/summary.json"

cat >"$out/failing.yaml" <<EOT
scene: failing
model: $src/models/lathe-c1/machine.yaml
backend: kinematic
duration: 0.5
expect:
  - {axis: Z, position: 123, tol: 0.001}
EOT
check run_failing_expectation 1 "FAILED: expect\[0\]: Z position 123" -- "$vmt" run "$out/failing.yaml" --out "$out/failing"

printf 'scene: bad\nmodel: %s\nduration: 1\ntimeline:\n  - move: {axis: Z, to: far, feed: 10}\n' \
  "$src/models/lathe-c1/machine.yaml" >"$out/bad.yaml"
check run_bad_scene 2 "bad.yaml:5:[0-9]+: timeline\[0\]\.move\.to: expected a number" -- "$vmt" run "$out/bad.yaml"
check run_missing_scene 2 "cannot open file" -- "$vmt" run "$out/nope.yaml"
# --until cuts the run short: expectations it does not reach count as failed.
check run_until 1 "0.500 s simulated" -- "$vmt" run "$src/scenes/drive-timeline.yaml" --backend kinematic --until 0.5 --out "$out/until"

# Block search from the command line (issue 8): --set writes the CNC objects at t = 0. The
# refused scene's search moved to N0020 (the plunge at Z158): its return from X26 Z180 is clear
# of the part, so the scene's expectation of error 507 now fails (exit 1) with the run intact.
check run_set_block_search 1 "FAILED: expect\[0\]: NC error at the end \(got hold\)" -- "$vmt" run "$src/scenes/block-search-refused.yaml" \
  --set P00.mc_cmd_bs_block_number_w=20 --set P00.mc_cmd_bs_covered_distance_w=0 --out "$out/set"
check run_set_block_search_event 0 '"continue_position":\{"X":40(\.0)?,"Z":158(\.0)?\}' -- cat "$out/set/events.jsonl"
check run_set_unknown_signal 2 "no gateway signal 'P00.nope'" -- "$vmt" run "$src/scenes/block-search-refused.yaml" --set P00.nope=1
check run_set_read_only 2 "not written by the PLC" -- "$vmt" run "$src/scenes/block-search-refused.yaml" --set P00.bahn_state.block_count_r=3
check run_set_not_a_number 2 "expects a number" -- "$vmt" run "$src/scenes/block-search-refused.yaml" --set P00.mc_cmd_bs_block_number_w=ten
check run_set_no_value 2 "expected NAME=VALUE" -- "$vmt" run "$src/scenes/block-search-refused.yaml" --set P00.mc_cmd_bs_type_w
sed 's/mc_cmd_bs_type_w: 4/mc_cmd_bs_type_w: many/' "$src/scenes/block-search-refused.yaml" \
  | sed "s#\.\./models#$src/models#; s#nc/stepped_shaft#$src/scenes/nc/stepped_shaft#" >"$out/bad_search.yaml"
check run_bad_block_search 2 "bad_search.yaml:[0-9]+:[0-9]+: nc\.block_search\.mc_cmd_bs_type_w: 'P00.mc_cmd_bs_type_w' expects a number" -- "$vmt" run "$out/bad_search.yaml"

check snapshot_a 0 "" -- "$vmt" snapshot "$src/scenes/drive-timeline.yaml" --at 0.5 --camera iso --out "$out/a.png" --width 320 --height 240
check snapshot_b 0 "" -- "$vmt" snapshot "$src/scenes/drive-timeline.yaml" --at 0.5 --camera iso --out "$out/b.png" --width 320 --height 240
check snapshot_same_bytes 0 "" -- cmp "$out/a.png" "$out/b.png"
# llvmpipe reads LP_NUM_THREADS once per process: compare separate processes.
check snapshot_1_thread 0 "" -- env LP_NUM_THREADS=1 "$vmt" snapshot "$src/scenes/drive-timeline.yaml" --at 0.5 --camera iso --out "$out/t1.png" --width 320 --height 240
check snapshot_4_threads 0 "" -- env LP_NUM_THREADS=4 "$vmt" snapshot "$src/scenes/drive-timeline.yaml" --at 0.5 --camera iso --out "$out/t4.png" --width 320 --height 240
check snapshot_threads_same_bytes 0 "" -- cmp "$out/t1.png" "$out/t4.png"
check snapshot_bad_camera 2 "no camera 'nope'" -- "$vmt" snapshot "$src/scenes/drive-timeline.yaml" --at 0.5 --camera nope --out "$out/c.png"
check snapshot_other 0 "" -- "$vmt" snapshot "$src/scenes/drive-timeline.yaml" --at 1.5 --camera iso --out "$out/c.png" --width 320 --height 240

check imgdiff_equal 0 "equal" -- "$vmt" imgdiff "$out/a.png" "$out/b.png"
check imgdiff_different 1 "different" -- "$vmt" imgdiff "$out/a.png" "$out/c.png" --diff "$out/diff.png"
check imgdiff_wrote_diff 0 "" -- test -s "$out/diff.png"
check imgdiff_size 1 "different sizes" -- "$vmt" imgdiff "$out/a.png" "$out/run/iso_3.2s.png"
check imgdiff_tolerant 0 "equal" -- "$vmt" imgdiff "$out/a.png" "$out/c.png" --tolerance 255
check imgdiff_missing 2 "nope.png" -- "$vmt" imgdiff "$out/a.png" "$out/nope.png"
echo "not a png" >"$out/text.png"
check imgdiff_not_png 2 "text.png" -- "$vmt" imgdiff "$out/a.png" "$out/text.png"
check imgdiff_golden 0 "equal" -- "$vmt" imgdiff "$src/tests/golden/drive-timeline/iso_3.2s.png" "$out/run/iso_3.2s.png" --tolerance 8 --allowed-fraction 0.002

# vmt golden (and the ctest golden_<scene> tests' use of it): tests/cli/golden_test.sh.

# vmt check: every error as file:line:column, exit 1; clean 0; a file it cannot read 2.
check check_clean 0 "stepped_shaft.mtc: mtc200, [0-9]+ blocks, 0 errors" -- "$vmt" check "$src/scenes/nc/stepped_shaft.mtc"
printf 'N10 G01 X10 F100\nN20 BRA .NOWHERE\n' >"$out/bad.mtc"
check check_errors 1 "bad.mtc:2:[0-9]+: error: " -- "$vmt" check "$out/bad.mtc" --dialect mtc200
check check_missing 2 "nope.mtc:0:0: error: cannot open file" -- "$vmt" check "$out/nope.mtc"
check check_directory 2 "cannot open file" -- "$vmt" check "$out"

# The signal table for the PLC engineer: the manuals' names, instantiated for the lathe.
check signals_csv 0 "P00C.REPOS,BOOL,PLC->NC,coil,0,1" -- "$vmt" signals "$src/models/lathe-c1/machine.yaml"
check signals_axis 0 "A01C.JGPOS" -- "$vmt" signals "$src/models/lathe-c1/machine.yaml"
check signals_spindle 0 "A03.ROTMOD_Q" -- "$vmt" signals "$src/models/lathe-c1/machine.yaml"
check signals_io 0 "QROTMODE,BOOL" -- "$vmt" signals "$src/models/lathe-c1/machine.yaml"
check signals_json 0 '"name": "P00S.CREST"' -- "$vmt" signals "$src/models/lathe-c1/machine.yaml" --format json
check signals_bad_format 2 "" -- "$vmt" signals "$src/models/lathe-c1/machine.yaml" --format xml
check signals_bad_model 2 "nope.yaml" -- "$vmt" signals "$src/models/nope.yaml"

echo "cli: $passes passed, $fails failed"
[ "$fails" -eq 0 ]
