#!/usr/bin/env bash
# Bad values and options answered with a message that places them: a scene or machine file's
# fault as file:line:col: yaml.path: reason, an option's with the option and its range; exit 2
# before any run, never a raw library text. Usage: messages_test.sh VMT SRC OUT
set -u
vmt=$1 src=$(cd "$2" && pwd) out=$3
rm -rf "$out" && mkdir -p "$out"
. "$(dirname "$0")/refusal_checks.sh"
good() {  # good NAME -- command...: exit 0
  local name=$1; shift 2
  if timeout 120 "$@" >"$out/$name.log" 2>&1 </dev/null; then
    echo "ok   $name"; passes=$((passes+1))
  else
    echo "FAIL $name: exit $?"; sed 's/^/    /' "$out/$name.log" | head -10; fails=$((fails+1))
  fi
}

model=$src/models/lathe-c1/machine.yaml
program=$src/scenes/nc/face_and_turn.mtc
# scene NAME TEXT: a kinematic scene of 0.1 s on lathe-c1 with TEXT after its header (line 5 on).
scene() {
  printf 'scene: %s\nmodel: %s\nbackend: kinematic\nduration: 0.1\n%b' "$1" "$model" "$2" >"$out/$1.yaml"
}

# The YAML text itself.
scene list_key '[a, b]: 1\n'
bad list_key "list_key.yaml:5:1: \(top level\): a key must be a name, not a list" -- "$vmt" run "$out/list_key.yaml" --out "$out/o"
scene null_key 'initial: {~: 3}\n'
bad null_key "null_key.yaml:5:11: initial: a key must be a name, not null" -- "$vmt" run "$out/null_key.yaml" --out "$out/o"
scene top_null_key '~: 3\n'
bad top_null_key "top_null_key.yaml:5:1: .*a key must be a name" -- "$vmt" run "$out/top_null_key.yaml" --out "$out/o"
scene duplicate 'initial: {Z: 300}\ninitial: {Z: 400}\n'
bad duplicate_key "duplicate.yaml:6:1: initial: duplicate key 'initial' \(first given at line 5:1\)" -- "$vmt" run "$out/duplicate.yaml" --out "$out/o"
scene duplicate_nested 'workpiece: {diameter: 60, length: 160, diameter: 50}\n'
bad duplicate_nested_key "duplicate_nested.yaml:5:40: workpiece.diameter: duplicate key" -- "$vmt" run "$out/duplicate_nested.yaml" --out "$out/o"
printf 'scene: caf\xe9\nmodel: %s\nbackend: kinematic\nduration: 0.1\n' "$model" >"$out/latin1.yaml"
bad latin1_scene "latin1.yaml:1:11: not UTF-8 text \(byte 0xE9\)" -- "$vmt" run "$out/latin1.yaml" --out "$out/latin1"
good latin1_left_no_output -- test ! -e "$out/latin1/summary.json"
scene syntax 'duration2: [1, 2\n'
bad yaml_syntax "syntax.yaml:[0-9]+:[0-9]+: YAML syntax error: a '\[' is not closed" -- "$vmt" run "$out/syntax.yaml" --out "$out/o"
# A byte order mark opens a scene (yaml-cpp) and an NC program alike.
printf '\xef\xbb\xbfscene: bom\nmodel: %s\nbackend: kinematic\nduration: 0.1\n' "$model" >"$out/bom.yaml"
good bom_scene -- "$vmt" run "$out/bom.yaml" --out "$out/bom"
printf '\xef\xbb\xbf' >"$out/bom.mtc" && cat "$program" >>"$out/bom.mtc"
good bom_nc_program -- "$vmt" check "$out/bom.mtc"
printf '\xef\xbb\xbfG01 X10 Q\nM30\n' >"$out/bom_bad.mtc"
check_bom() { "$vmt" check "$out/bom_bad.mtc"; [ $? = 1 ] && exit 2; }
bad bom_nc_column "bom_bad.mtc:1:9: error" -- bash -c "$(declare -f check_bom); vmt=$vmt out=$out check_bom"

# Names and numbers in their places.
scene unknown_axis 'initial: {Q: 3}\n'
bad unknown_initial_axis "unknown_axis.yaml:5:11: initial.Q: no axis 'Q'" -- "$vmt" run "$out/unknown_axis.yaml" --out "$out/o"
scene big_duration '' && sed -i 's/^duration: 0.1/duration: 1e308/' "$out/big_duration.yaml"
bad absurd_duration "big_duration.yaml:4:11: duration: must be in 0..86400, got 1e308" -- "$vmt" run "$out/big_duration.yaml" --out "$out/o"
scene override "nc: {program: $program, override: 1e308}\n"
bad absurd_override "override.yaml:5:[0-9]+: nc.override: must be in 0..200" -- "$vmt" run "$out/override.yaml" --out "$out/o"
scene negative_override "nc: {program: $program, override: -5}\n"
bad negative_override "nc.override: must be in 0..200" -- "$vmt" run "$out/negative_override.yaml" --out "$out/o"
scene timeout 'timeline:\n  - wait_until: {axis: Z, in_position: true, timeout: -1}\n'
bad negative_timeout "timeout.yaml:6:[0-9]+: timeline\[0\]\.wait_until\.timeout: must be in 0..86400" -- "$vmt" run "$out/timeout.yaml" --out "$out/o"
scene snap_at 'snapshots:\n  - {camera: iso, at: -1}\n'
bad snapshot_negative_at "snap_at.yaml:6:[0-9]+: snapshots\[0\]\.at: must be in 0..86400" -- "$vmt" run "$out/snap_at.yaml" --out "$out/o"
scene snap_file 'snapshots:\n  - {camera: iso, at: 0.05, file: ""}\n'
bad snapshot_empty_file "snap_file.yaml:6:[0-9]+: snapshots\[0\]\.file: a plain file name" -- "$vmt" run "$out/snap_file.yaml" --out "$out/snap_file"
good snapshot_empty_file_no_run -- test ! -e "$out/snap_file/trace.csv"
scene tool "nc:\n  program: $program\n  tools:\n    - {T: 1, X: 1e308}\n"
bad absurd_tool_length "tool.yaml:8:[0-9]+: nc.tools\[0\]\.X: must be in -10000..10000" -- "$vmt" run "$out/tool.yaml" --out "$out/o"
scene offset "nc:\n  program: $program\n  zero_offsets: {G54: {Z: -1e308}}\n"
bad absurd_zero_offset "offset.yaml:7:[0-9]+: nc.zero_offsets.G54.Z: must be in -100000..100000" -- "$vmt" run "$out/offset.yaml" --out "$out/o"
scene feed 'timeline:\n  - move: {axis: Z, to: 300, feed: 1e308}\n'
bad absurd_feed "feed.yaml:6:[0-9]+: timeline\[0\]\.move\.feed: must be in -10000000..10000000" -- "$vmt" run "$out/feed.yaml" --out "$out/o"
scene rpm 'timeline:\n  - speed: {axis: S1, rpm: 1e300}\n'
bad absurd_rpm "rpm.yaml:6:[0-9]+: timeline\[0\]\.speed\.rpm: must be in -100000..100000" -- "$vmt" run "$out/rpm.yaml" --out "$out/o"
scene initial_word "nc:\n  program: $program\n  initial: [T99999999999]\n"
bad huge_initial_word "initial_word.yaml:7:[0-9]+: nc.initial\[0\]" -- "$vmt" run "$out/initial_word.yaml" --out "$out/o"
scene covered "nc:\n  program: $program\n  block_search: {mc_cmd_bs_type_w: 4, mc_cmd_bs_covered_distance_w: 1500}\n"
bad covered_distance "covered.yaml:7:[0-9]+: nc.block_search.mc_cmd_bs_covered_distance_w: .*must be in 0..1000" -- "$vmt" run "$out/covered.yaml" --out "$out/o"
# A machine file's numbers: a clutch that engages in negative time.
mkdir -p "$out/machine"
cp -r "$src/models/lathe-c1/." "$out/machine/"
sed -i '0,/engage_time: [0-9.]*/s//engage_time: -0.2/' "$out/machine/machine.yaml"
good machine_edited -- grep -q "engage_time: -0.2" "$out/machine/machine.yaml"
bad negative_engage_time "machine.yaml:[0-9]+:[0-9]+: couplings\[[0-9]+\]\.engage_time: must be in 0..600" -- "$vmt" signals "$out/machine/machine.yaml"

# Options: the option and its range, before any work.
s=$src/scenes/drive-timeline.yaml
touch "$out/a_file"
bad until_nan "--until: must be a finite number of seconds in 0.00025..86400, got 'nan'" -- "$vmt" run "$s" --until nan --out "$out/o"
bad until_huge "--until: must be a finite number of seconds" -- "$vmt" run "$s" --until 1e308 --out "$out/o"
bad until_negative "--until: must be a finite number" -- "$vmt" run "$s" --until -1 --out "$out/o"
bad out_is_file "--out: .*a_file: is not a directory" -- "$vmt" run "$s" --out "$out/a_file"
bad out_empty "--out: needs a folder name" -- "$vmt" run "$s" --out ""
bad snapshot_at_nan "--at: must be a finite number of seconds in 0..86400, got 'nan'" -- "$vmt" snapshot "$s" --at nan --out "$out/x.png"
bad snapshot_at_huge "--at: must be a finite number" -- "$vmt" snapshot "$s" --at 1e308 --out "$out/x.png"
bad snapshot_out_folder "--out: .*: is a directory, not a file" -- "$vmt" snapshot "$s" --at 0.1 --out "$out"
bad snapshot_width "--width: must be a whole number in 16..4096, got '1e9'" -- "$vmt" snapshot "$s" --at 0.1 --out "$out/x.png" --width 1e9
bad imgdiff_fraction_nan "--allowed-fraction: must be a finite fraction in 0..1, got 'nan'" -- "$vmt" imgdiff "$out/a.png" "$out/b.png" --allowed-fraction nan
bad imgdiff_tolerance "--tolerance: must be a whole number in 0..255" -- "$vmt" imgdiff "$out/a.png" "$out/b.png" --tolerance -1
bad study_max_cases "--max-cases: must be a whole number in 1..1000000000, got '-1'" -- "$vmt" study repos "$s" --out "$out/study" --max-cases -1
bad study_every_ms "--every-ms: must be a finite number of ms in 1..10000000, got 'nan'" -- "$vmt" study repos "$s" --out "$out/study" --every-ms nan
bad study_jobs "--jobs: must be a whole number in 1..256, got '0'" -- "$vmt" study repos "$s" --out "$out/study" --jobs 0
bad study_out_file "--out: .*: is not a directory" -- "$vmt" study repos "$s" --out "$out/a_file"
bad study_compare_threshold "--threshold: must be a finite number of mm" -- "$vmt" study compare "$out/a" "$out/b" --threshold inf
bad serve_until "--until: must be a finite number of seconds" -- "$vmt" serve "$s" --until inf
bad serve_plc_timeout "--plc-timeout: must be a finite number of ms" -- "$vmt" serve "$s" --plc-timeout nan
bad serve_idle_timeout "--idle-timeout: must be a finite number of seconds" -- "$vmt" serve "$s" --idle-timeout -3
bad golden_out_file "--out: .*: is not a directory" -- "$vmt" golden check "$s" --golden "$out/g" --out "$out/a_file"

# A file name that is not UTF-8 reaches the JSON files as U+FFFD, never an exception after the run.
latin1_name=$(printf 'caf\xe9')
printf 'scene: named\nmodel: %s\nbackend: kinematic\nduration: 0.1\n' "$model" >"$out/$latin1_name.yaml"
check_golden_json() {
  "$vmt" golden check "$out/$latin1_name.yaml" --golden "$out/g" --out "$out/gout" --json "$out/golden.json"
  [ $? = 1 ] && grep -q '"scene": "caf' "$out/golden.json" && exit 2
}
bad golden_json_latin1_name "FAIL caf" -- bash -c "$(declare -f check_golden_json); vmt=$vmt out=$out latin1_name=$latin1_name check_golden_json"

echo "$passes passed, $fails failed"
[ "$fails" = 0 ]
