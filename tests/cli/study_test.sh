#!/bin/bash
# vmt study as a user meets it: a tiny study, a rerun that skips every case, a case saved and
# watched from the report (vmt study replay, vmt view of the study folder), shards (and worker
# processes, and GNU parallel if installed) that merge into the unsharded result, two versions
# of a REPOS subroutine compared (vmt study compare).
# Usage: study_test.sh VMT SOURCE_DIR WORK_DIR
set -euo pipefail
vmt=$1 src=$2 work=$3
scene=$src/tests/sim/study/tiny-study.yaml
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAILED: $*" >&2; exit 1; }
sorted() { sort "$1/cases.jsonl"; }

"$vmt" study repos "$scene" --out whole > whole.txt
cat whole.txt
n=$(wc -l < whole/cases.jsonl)
[ "$n" -ge 4 ] || fail "expected at least 4 cases, got $n"
[ "$(wc -l < whole/cases.csv)" -eq $((n + 1)) ] || fail "cases.csv: header + one row per case"
grep -q '"verdict":"collision"' whole/cases.jsonl || fail "no collision"
grep -q '"verdict":"clear"' whole/cases.jsonl || fail "no clear case"
grep -q '<svg' whole/report.html || fail "report.html has no SVG"
# The worst cases' pictures (a collision at its first contact, the tightest clear case),
# named after the case, linked from the report.
[ -f whole/snapshots.json ] || fail "no snapshots.json"
shots=$(ls whole/snapshots/*.png | wc -l)
[ "$shots" -ge 2 ] || fail "expected at least 2 pictures, got $shots"
grep -q '<a href="snapshots/[^"]*\.png">' whole/report.html || fail "report.html links no picture"

# A rerun skips what the folder holds; a study cut short keeps its whole lines.
"$vmt" study repos "$scene" --out whole | grep -q "(0 run, $n already there)" || fail "rerun ran cases"
[ "$(wc -l < whole/cases.jsonl)" -eq "$n" ] || fail "rerun changed the case count"
mkdir -p cut && head -n 2 whole/cases.jsonl > cut/cases.jsonl && printf '{"case":"torn' >> cut/cases.jsonl
"$vmt" study repos "$scene" --out cut | grep -q "($((n - 2)) run, 2 already there)" || fail "cut study"
diff <(sorted whole) <(sorted cut) > /dev/null || fail "a resumed study differs"

# Shards merged = the whole study; worker processes too.
"$vmt" study repos "$scene" --out s1 --shard 1/2 > /dev/null
"$vmt" study repos "$scene" --out s2 --shard 2/2 > /dev/null
"$vmt" study merge s1 s2 --out merged > /dev/null
diff <(sorted whole) <(sorted merged) > /dev/null || fail "merged shards differ from the whole"
grep -q '<svg' merged/report.html || fail "merged report.html"
"$vmt" study repos "$scene" --out jobs --jobs 2 > /dev/null
diff <(sorted whole) <(sorted jobs) > /dev/null || fail "--jobs 2 differs from one job"
cmp whole/cases.jsonl jobs/cases.jsonl || fail "cases.jsonl: not the same bytes with --jobs 2"
# However the cases share their run-ups (in memory, forked, or none: each from the start), the
# same bytes; a sharing the study does not know is refused.
for run_ups in fork start; do
  "$vmt" study repos "$scene" --out "$run_ups" --run-ups "$run_ups" --snapshots 0 > /dev/null
  cmp whole/cases.jsonl "$run_ups/cases.jsonl" || fail "cases.jsonl differs with --run-ups $run_ups"
done
set +e
"$vmt" study repos "$scene" --out bad --run-ups threads > bad.txt 2>&1
code=$?
set -e
[ "$code" -eq 2 ] || fail "--run-ups threads: exit $code, not 2"
grep -q "run-ups" bad.txt || fail "--run-ups threads: the message names no option: $(cat bad.txt)"
"$vmt" study repos "$scene" --out noshots --snapshots 0 > /dev/null
[ ! -e noshots/snapshots ] || fail "--snapshots 0 took pictures"
cmp whole/cases.jsonl noshots/cases.jsonl || fail "cases.jsonl depends on the pictures"

# A case watched: saved on demand (vmt study replay), then the study's report served by vmt view,
# each case a link that opens a replay station of its own; the merged folder knows its scene too.
id=$(grep -o '"case":"[^"]*over the chuck/repositioning"' whole/cases.jsonl | head -1 | cut -d'"' -f4)
[ -n "$id" ] || fail "no case over the chuck to replay"
"$vmt" study replay whole "$id" > replay.txt || fail "vmt study replay: $(cat replay.txt)"
case_dir=$(sed -n 's/^case .*: \(.*\)\/{trace.csv.*/\1/p' replay.txt)
for f in trace.csv events.jsonl summary.json case.json; do
  [ -f "$case_dir/$f" ] || fail "the saved case has no $f: $(cat replay.txt)"
done
grep -q '"event":"path_guard"' "$case_dir/events.jsonl" || fail "the saved collision case has no PathGuard event"
grep -q '"verdict": "collision"' "$case_dir/case.json" || fail "the saved case's verdict differs from the study's"
[ -f merged/study.json ] || fail "the merged study does not know its scene"
set +e
"$vmt" study replay whole "no/such/case" 2> err.txt; rc=$?
set -e
[ $rc -eq 2 ] && grep -q "has no case" err.txt || fail "an unknown case: exit $rc, $(cat err.txt)"
grep -q 'href="replay?case=' whole/report.html || fail "report.html links no case to its replay"
timeout 300 "$vmt" view whole --http 127.0.0.1:0 > view.log 2>&1 &
view_pid=$!
port=
for _ in $(seq 200); do
  port=$(sed -n 's|.*report on http://127.0.0.1:\([0-9]*\)/.*|\1|p' view.log)
  [ -n "$port" ] && break
  sleep 0.05
done
[ -n "$port" ] || fail "vmt view of a study folder did not start: $(cat view.log)"
curl -sf "http://127.0.0.1:$port/report.html" -o served-report.html || fail "the study's report is not served"
grep -q '<svg' served-report.html || fail "the served report has no SVG"
link=$(grep -o 'href="replay?case=[^"]*"' served-report.html | tail -1 | cut -d'"' -f2 | sed 's/&amp;/\&/g')
to=$(curl -s -o /dev/null -w '%{http_code} %{redirect_url}' "http://127.0.0.1:$port/$link")
case "$to" in
  "302 http://127.0.0.1:"*/) ;;
  *) fail "following $link: $to" ;;
esac
curl -sf "${to#302 }api/model" -o case-model.json || fail "the case's station does not answer"
grep -q '"pace":"replay"' case-model.json || fail "the case's station is not a replay"
code=$(curl -s -o /dev/null -w '%{http_code}' "http://127.0.0.1:$port/replay?case=no%2Fsuch")
[ "$code" = 404 ] || fail "an unknown case's replay: HTTP $code"
if [ -x /usr/bin/chromedriver ] && /usr/bin/python3 -c 'import selenium' 2>/dev/null; then
  timeout 200 /usr/bin/python3 "$src/tests/station/study_report_page.py" \
    --url "http://127.0.0.1:$port/report.html" > report-page.log 2>&1 ||
    fail "clicking a case in the report (chromium): $(tail -5 report-page.log)"
  cat report-page.log
fi
kill -INT $view_pid; wait $view_pid || true
grep -q "differs from the recorded" view.log && fail "a case's replay digest differs: $(cat view.log)"

# GNU parallel, as on a workstation without Slurm.
if command -v parallel > /dev/null; then
  parallel --will-cite "$vmt" study repos "$scene" --out p{} --shard {}/3 ::: 1 2 3 > /dev/null
  "$vmt" study merge p1 p2 p3 --out pmerged > /dev/null
  diff <(sorted whole) <(sorted pmerged) > /dev/null || fail "GNU parallel shards differ"
  echo "GNU parallel: shards merged equal the whole"
else
  echo "GNU parallel not installed: its part skipped"
fi

# Two versions of the REPOS subroutine compared case by case (vmt study compare): program 99
# returning X first, then the same file with Z first; the case over the chuck stops crashing.
mkdir -p v/nc
sed "s|\.\./\.\./\.\./|$src/|; s|subroutines: \[.*\]|subroutines: [nc/99.mtc]|" "$scene" > v/study.yaml
cp "$src/scenes/nc/99.mtc" v/nc/99.mtc
"$vmt" study repos v/study.yaml --out v1 --snapshots 0 > /dev/null
cp "$src/scenes/nc/99_safe.mtc" v/nc/99.mtc
"$vmt" study repos v/study.yaml --out v2 --snapshots 0 > /dev/null
"$vmt" study compare v1 v2 --html cmp.html > cmp.txt || fail "vmt study compare: exit $?"
cat cmp.txt
grep -q "cases in both, 0 only in A, 0 only in B" cmp.txt || fail "compare: the cases do not match"
grep -q "crash -> clear: 1" cmp.txt || fail "compare: the crash over the chuck did not go"
grep -q "over the chuck/repositioning: crash -> clear" cmp.txt || fail "compare: the changed case"
grep -q "<b>clear</b>" cmp.html || fail "compare: no page"
"$vmt" study compare whole whole --html same.html | grep -q "^0 changed class" ||
  fail "a study compared with itself changed"
# The report of the first concludes, the crash named with its parts and program region.
grep -q "<h2>Conclusions</h2>" v1/report.html || fail "report.html: no conclusions"
grep -q "nc/99.mtc fails in 1 of" v1/report.html || fail "report.html: no sentence for program 99"
grep -q "is clear in all" v2/report.html || fail "report.html: program 99 Z first not clear"
grep -q '"contact_class":"crash"' v1/cases.jsonl || fail "cases.jsonl: no contact class"
set +e
"$vmt" study compare v1 no-such-folder 2> err.txt; rc=$?
set -e
[ $rc -eq 2 ] && grep -q "not a study folder" err.txt || fail "compare with no study: exit $rc"

# Bad input: exit 2 with a message.
set +e
"$vmt" study repos "$scene" --out bad --shard 3/2 2> err.txt; [ $? -eq 2 ] || fail "--shard 3/2"
"$vmt" study repos "$src/scenes/repos-collision.yaml" --out bad 2> err.txt; rc=$?
set -e
[ $rc -eq 2 ] || fail "a scene without study: exit $rc"
grep -q "study" err.txt || fail "no message for a scene without study:"
echo "study cli: ok"
