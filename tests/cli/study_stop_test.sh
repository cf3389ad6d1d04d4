#!/usr/bin/env bash
# SIGTERM and SIGINT stop vmt study as they stop vmt run: a message saying how many cases
# finished, exit 3, no worker process left, cases.jsonl in whole lines; the same command again
# resumes the study, and the result is byte for byte that of a study never stopped. With two
# jobs the cases run in worker processes; with one they run in the study's own process, which
# forks none.
# Usage: study_stop_test.sh VMT SRC OUT
set -u
vmt=$1 src=$2 out=$3
rm -rf "$out" && mkdir -p "$out" && cd "$out"
fails=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }
ok() { echo "ok   $*"; }
study=$src/tests/sim/study/tiny-study.yaml
# 2 retracts x every 60 ms of a 7.8 s program: 260 cases, some seconds with two workers;
# one picture per subroutine, so that the resumed study renders as the whole one does.
args_of() { echo --every-ms 60 --jobs "$1" --snapshots 1; }

# whole_lines FILE: every line of FILE is a complete JSON case and the file ends with a newline.
whole_lines() {
  python3 -c 'import json,sys
t = open(sys.argv[1], "rb").read()
assert t.endswith(b"\n") or not t
for l in t.splitlines(): assert "case" in json.loads(l)' "$1" 2>/dev/null
}
# family PID: PID's child processes and theirs (the workers, their cases' copies).
family() {
  local p kids=""
  for p in $(pgrep -P "$1"); do kids="$kids $p $(family "$p")"; done
  echo "$kids"
}
# gone PIDS...: true once none of PIDS is there (within 5 s: a case's copy dies with its
# parent, a moment after it).
gone() {
  local p left
  for _ in $(seq 1 50); do
    left=""
    for p in "$@"; do kill -0 "$p" 2>/dev/null && left="$left $p"; done
    [ -z "$left" ] && return 0
    sleep 0.1
  done
  echo "$left"
  return 1
}

for jobs in 2 1; do
read -r -a args <<<"$(args_of $jobs)"
whole=whole$jobs
"$vmt" study repos "$study" "${args[@]}" --out $whole >$whole.log 2>&1 ||
  { echo "FAIL the study never stopped: $(tail -3 $whole.log)"; exit 1; }
total=$(wc -l <$whole/cases.jsonl)
sigs="TERM INT"
[ "$jobs" = 1 ] && sigs=TERM

for sig in $sigs; do
  dir=stopped$sig-$jobs
  "$vmt" study repos "$study" "${args[@]}" --out "$dir" >"$dir.log" 2>&1 &
  pid=$!
  # Until the workers have finished a few cases (the reference run comes first).
  for _ in $(seq 1 300); do
    [ -f "$dir/cases.jsonl" ] && [ "$(wc -l <"$dir/cases.jsonl")" -ge 20 ] && break
    sleep 0.05
  done
  procs=$(family "$pid")
  kill -"$sig" "$pid"
  wait "$pid"
  code=$?
  finished=$(wc -l <"$dir/cases.jsonl")
  if [ "$code" != 3 ]; then
    fail "SIG$sig: exit $code, wanted 3"; sed 's/^/    /' "$dir.log" | tail -3
  elif [ "$jobs" -gt 1 ] && [ -z "$procs" ]; then fail "SIG$sig: no worker process seen"
  elif [ "$jobs" = 1 ] && [ -n "$procs" ]; then fail "SIG$sig: one job forked:$procs"
  elif ! left=$(gone $procs); then
    fail "SIG$sig: processes outlive the stopped study:$left"
    for p in $left; do kill -9 "$p" 2>/dev/null; done
  elif ! whole_lines "$dir/cases.jsonl"; then fail "SIG$sig: cases.jsonl has a cut line"
  elif ! [ "$finished" -gt 0 ] || ! [ "$finished" -lt "$total" ]; then
    fail "SIG$sig: $finished of $total cases kept (wanted some, not all)"
  elif ! grep -q "stopped by SIG$sig: $finished of $total cases finished" "$dir.log"; then
    fail "SIG$sig: no message saying so"; sed 's/^/    /' "$dir.log" | tail -3
  elif ls -a "$dir" | grep -qE '^\.(reference|snapshot)-|\.tmp-'; then
    fail "SIG$sig: scratch left: $(ls -a "$dir" | tr '\n' ' ')"
  else
    ok "SIG$sig, $jobs job(s): exit 3, $(echo $procs | wc -w) processes ended, $finished of $total cases kept whole"
  fi
  # The same command again finishes the study: the same bytes as the study never stopped.
  "$vmt" study repos "$study" "${args[@]}" --out "$dir" >"$dir-resumed.log" 2>&1 ||
    fail "SIG$sig: the resumed study failed: $(tail -3 "$dir-resumed.log")"
  if ! grep -q "($((total - finished)) run, $finished already there)" "$dir-resumed.log"; then
    fail "SIG$sig: the resumed study did not skip the finished cases: $(head -1 "$dir-resumed.log")"
  elif ! diff -r $whole "$dir" >"$dir.diff"; then
    fail "SIG$sig: resumed differs from the whole study:"; head -5 "$dir.diff"
  else ok "SIG$sig, $jobs job(s): resumed, every file byte-identical to the study never stopped"; fi
done
done

# Stopped at once, most likely in its reference run: exit 3, no scratch folder left.
read -r -a args <<<"$(args_of 2)"
"$vmt" study repos "$study" "${args[@]}" --out early >early.log 2>&1 &
pid=$!
for _ in $(seq 1 200); do [ -n "$(ls -a early 2>/dev/null | grep '^\.reference-')" ] && break; sleep 0.01; done
kill -TERM "$pid"
wait "$pid"
code=$?
if [ "$code" = 0 ] && [ -f early/report.html ]; then
  echo "(the reference run ended before the signal: nothing to check)"
elif [ "$code" != 3 ]; then fail "stopped in the reference run: exit $code, wanted 3"; tail -3 early.log
elif ! grep -q "stopped by SIGTERM" early.log; then fail "stopped in the reference run: no message"
elif ls -a early | grep -qE '^\.(reference|snapshot)-|\.tmp-'; then
  fail "stopped in the reference run: left $(ls -a early | tr '\n' ' ')"
else ok "SIGTERM at once: exit 3, no scratch left ($(grep -o 'during the reference run' early.log))"; fi

[ "$fails" = 0 ] || { echo "$fails failure(s)"; exit 1; }
echo "all passed"
