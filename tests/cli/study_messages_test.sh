#!/usr/bin/env bash
# A study plan's numbers and vmt study's options, each refused with its place and its range:
# the plan's as file:line:col: study.path: must be in LO..HI, an option's with the option and
# its range; exit 2 before the reference run, never a raw library text.
# Usage: study_messages_test.sh VMT SRC OUT
set -u
vmt=$1 src=$(cd "$2" && pwd) out=$3
rm -rf "$out" && mkdir -p "$out"
bad_timeout=30
. "$(dirname "$0")/refusal_checks.sh"

# plan NAME SED: tests/sim/study/tiny-study.yaml (its paths made absolute) edited by SED.
plan() {
  sed -e "s|\.\./\.\./\.\./|$src/|g" -e "$2" "$src/tests/sim/study/tiny-study.yaml" >"$out/$1.yaml"
}

# The plan's numbers.
plan every_huge 's/every_ms: 3000/every_ms: 1e8/'
bad plan_every_ms_huge "every_huge.yaml:15:25: study.interrupt.every_ms: must be in 1..10000000, got 1e8" -- "$vmt" study repos "$out/every_huge.yaml" --out "$out/study-every_huge"
plan every_small 's/every_ms: 3000/every_ms: 0.5/'
bad plan_every_ms_small "study.interrupt.every_ms: must be in 1..10000000, got 0.5" -- "$vmt" study repos "$out/every_small.yaml" --out "$out/study-every_small"
plan every_nan 's/every_ms: 3000/every_ms: .nan/'
bad plan_every_ms_nan "every_nan.yaml:15:25: study.interrupt.every_ms: expected a finite number" -- "$vmt" study repos "$out/every_nan.yaml" --out "$out/study-every_nan"
plan per_mille_big 's/{every_ms: 3000}/{per_mille: [250, 1001]}/'
bad plan_per_mille_range "study.interrupt.per_mille\[1\]: must be in 0..1000, got 1001" -- "$vmt" study repos "$out/per_mille_big.yaml" --out "$out/study-per_mille_big"
plan per_mille_frac 's/{every_ms: 3000}/{per_mille: [1.5]}/'
bad plan_per_mille_whole "study.interrupt.per_mille\[0\]: expected a whole number in 0..1000" -- "$vmt" study repos "$out/per_mille_frac.yaml" --out "$out/study-per_mille_frac"
points=$(seq -s, 0 1001)  # 1002 points: more than 0..1000 holds
plan per_mille_many "s/{every_ms: 3000}/{per_mille: [$points]}/"
bad plan_per_mille_count "study.interrupt.per_mille: expected a list of 1..1001 points" -- "$vmt" study repos "$out/per_mille_many.yaml" --out "$out/study-per_mille_many"
plan hold_huge 's/^  modes:/  hold: 1e308\n  modes:/'
bad plan_hold "study.hold: must be in 0.01..60, got 1e308" -- "$vmt" study repos "$out/hold_huge.yaml" --out "$out/study-hold_huge"
plan timeout_neg 's/^  modes:/  timeout: -1\n  modes:/'
bad plan_timeout "study.timeout: must be in 0.1..3600, got -1" -- "$vmt" study repos "$out/timeout_neg.yaml" --out "$out/study-timeout_neg"
plan timeout_inf 's/^  modes:/  timeout: .inf\n  modes:/'
bad plan_timeout_inf "study.timeout: expected a finite number" -- "$vmt" study repos "$out/timeout_inf.yaml" --out "$out/study-timeout_inf"
plan jog_huge 's/{axis: X, mm: 20}/{axis: X, mm: 1e308}/'
bad plan_jog_mm "study.retracts\[0\].jogs\[0\].mm: must be in -10000..10000, got 1e308" -- "$vmt" study repos "$out/jog_huge.yaml" --out "$out/study-jog_huge"
plan jog_zero 's/{axis: X, mm: 20}/{axis: X, mm: 0}/'
bad plan_jog_zero "study.retracts\[0\].jogs\[0\].mm: expected a distance, not 0" -- "$vmt" study repos "$out/jog_zero.yaml" --out "$out/study-jog_zero"
plan jog_to 's/{axis: X, mm: 20}/{axis: X, to: -1e308}/'
bad plan_jog_to "study.retracts\[0\].jogs\[0\].to: must be in -10000..10000, got -1e308" -- "$vmt" study repos "$out/jog_to.yaml" --out "$out/study-jog_to"

# The options, before any work.
plan good 's/x/x/'
bad option_shard_order "--shard: must be K/N with 1 <= K <= N <= 100000, e.g. 2/8, got '3/2'" -- "$vmt" study repos "$out/good.yaml" --out "$out/study-good" --shard 3/2
bad option_shard_zero "--shard: must be K/N with 1 <= K <= N <= 100000, e.g. 2/8, got '1/0'" -- "$vmt" study repos "$out/good.yaml" --out "$out/study-good" --shard 1/0
bad option_shard_huge "--shard: must be K/N .*, got '1/99999999999'" -- "$vmt" study repos "$out/good.yaml" --out "$out/study-good" --shard 1/99999999999
bad option_shard_text "--shard: must be K/N .*, got 'two'" -- "$vmt" study repos "$out/good.yaml" --out "$out/study-good" --shard two
bad option_per_mille_range "--per-mille: must be 1..1001 comma-separated whole numbers in 0..1000, e.g. 250,750, got '250,1001'" -- "$vmt" study repos "$out/good.yaml" --out "$out/study-good" --per-mille 250,1001
bad option_per_mille_empty "--per-mille: must be .*, got '5,,6'" -- "$vmt" study repos "$out/good.yaml" --out "$out/study-good" --per-mille 5,,6
bad option_per_mille_many "--per-mille: must be 1..1001 " -- "$vmt" study repos "$out/good.yaml" --out "$out/study-good" --per-mille "$points"
bad option_every_and_per_mille "--every-ms excludes --per-mille" -- "$vmt" study repos "$out/good.yaml" --out "$out/study-good" --every-ms 10 --per-mille 500
bad option_every_ms_small "--every-ms: must be a finite number of ms in 1..10000000, got '0.5'" -- "$vmt" study repos "$out/good.yaml" --out "$out/study-good" --every-ms 0.5
bad option_every_ms_huge "--every-ms: must be a finite number of ms in 1..10000000, got '1e8'" -- "$vmt" study repos "$out/good.yaml" --out "$out/study-good" --every-ms 1e8
bad option_snapshots "--snapshots: must be a whole number in 0..100, got '-1'" -- "$vmt" study repos "$out/good.yaml" --out "$out/study-good" --snapshots -1
for name in every_huge per_mille_big hold_huge jog_huge good; do
  [ -e "$out/study-$name/reference.json" ] && { echo "FAIL $name: the reference ran"; fails=$((fails+1)); }
done

echo "$passes passed, $fails failed"
[ "$fails" = 0 ]
