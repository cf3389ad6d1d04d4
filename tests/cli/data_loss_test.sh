#!/usr/bin/env bash
# Nothing lost, nothing half-written: a full disk is exit 2 naming the file, with no partial
# file left under its name; SIGTERM / SIGINT stop vmt run with complete files and a summary
# that says so (exit 3); a study's workers die with it; a corrupt cases.jsonl is refused.
# The full disk is a small tmpfs where it can be mounted (root on a VM), else a file size limit
# (ulimit -f) and /dev/full. Usage: data_loss_test.sh VMT SRC OUT
set -u
vmt=$1 src=$2 out=$3
# The small filesystems mounted under OUT (also those of a run killed before its cleanup).
unmount_all() {
  local m
  for m in $(awk -v o="$out/" 'index($2, o) == 1 {print $2}' /proc/mounts 2>/dev/null); do
    umount "$m" 2>/dev/null
  done
}
unmount_all
rm -rf "$out" && mkdir -p "$out" && cd "$out"
fails=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }
ok() { echo "ok   $*"; }
json_ok() { python3 -c 'import json,sys; json.load(open(sys.argv[1]))' "$1" 2>/dev/null; }
jsonl_ok() {
  python3 -c 'import json,sys; [json.loads(l) for l in open(sys.argv[1])]' "$1" 2>/dev/null
}
jog=$src/scenes/jog.yaml
study=$src/tests/sim/study/tiny-study.yaml
trap unmount_all EXIT

# full_dir NAME KB: a folder on a filesystem of KB kilobytes ("" when none can be mounted).
full_dir() {
  mkdir -p "$out/$1"
  # DATA_LOSS_NO_TMPFS=1 tries the way a container without mount rights goes.
  if [ -z "${DATA_LOSS_NO_TMPFS:-}" ] && mount -t tmpfs -o "size=${2}k" tmpfs "$out/$1" 2>/dev/null; then
    echo "$out/$1"
  fi
}
# no_partial DIR FILE...: none of FILE under DIR, and no temporary beside them.
no_partial() {
  local dir=$1 f
  shift
  for f in "$@"; do [ -e "$dir/$f" ] && return 1; done
  ! ls -a "$dir" | grep -q '\.tmp-'
}
# expect_write_error NAME FILE LOG CODE: exit 2 and "cannot write .../FILE: REASON" in LOG.
expect_write_error() {
  if [ "$4" != 2 ]; then
    fail "$1: exit $4, wanted 2"; sed 's/^/    /' "$3" | tail -5; return 1
  fi
  if ! grep -qE "cannot write [^ ]*$2: (No space left on device|File too large)" "$3"; then
    fail "$1: no message naming $2"; sed 's/^/    /' "$3" | tail -5; return 1
  fi
}

# --- A full disk ---------------------------------------------------------------------------
disk=$(full_dir disk 256)
if [ -n "$disk" ]; then
  echo "(a 256 KB tmpfs)"
  # The trace (1.1 MB) does not fit: its temporary goes, and the summary still says what ran.
  "$vmt" run "$jog" --out "$disk/run" >run-full.log 2>&1
  if expect_write_error "run, trace on a full disk" trace.csv run-full.log $?; then
    if ! no_partial "$disk/run" trace.csv; then fail "run: a partial trace.csv is left"
    elif ! json_ok "$disk/run/summary.json"; then fail "run: summary.json not complete JSON"
    elif ! grep -q '"write_errors"' "$disk/run/summary.json"; then fail "run: summary names no error"
    elif ! jsonl_ok "$disk/run/events.jsonl"; then fail "run: events.jsonl has a cut line"
    else ok "run, trace on a full disk: exit 2, no partial trace, summary complete"; fi
  fi
  rm -rf "${disk:?}"/*
  # A picture that does not fit (15 KB into 8 KB).
  small=$(full_dir small 8)
  "$vmt" snapshot "$jog" --at 0.1 --out "$small/shot.png" >shot-full.log 2>&1
  expect_write_error "snapshot on a full disk" shot.png shot-full.log $? &&
    { no_partial "$small" shot.png && ok "snapshot on a full disk: exit 2, no partial PNG" ||
        fail "snapshot: a partial PNG is left"; }
  # A study: its reference run's trace does not fit; no work folder is left behind.
  "$vmt" study repos "$study" --out "$disk/study" >study-full.log 2>&1
  code=$?
  if expect_write_error "study on a full disk" "(trace.csv|events.jsonl)" study-full.log $code; then
    if ls -a "$disk/study" | grep -qE '^\.(reference|snapshot)-|\.tmp-'; then
      fail "study: a temporary folder or file is left: $(ls -a "$disk/study" | tr '\n' ' ')"
    else ok "study on a full disk: exit 2, no temporary left"; fi
  fi
  # vmt serve: stopped by its idle timeout with no PLC; one page of disk for its four files.
  tiny=$(full_dir tiny 4)
  "$vmt" serve "$jog" --modbus 127.0.0.1:0 --idle-timeout 1 --out "$tiny" >serve-full.log 2>&1
  expect_write_error "serve on a full disk" "(trace.csv|summary.json|serve.json)" serve-full.log $? &&
    { no_partial "$tiny" trace.csv && ok "serve on a full disk: exit 2, each lost file named" ||
        fail "serve: a partial trace.csv is left"; }
else
  echo "(no tmpfs: a file size limit and /dev/full)"
  mkdir -p limited
  (ulimit -f 256; "$vmt" run "$jog" --out limited) >run-full.log 2>&1
  expect_write_error "run, trace over the size limit" trace.csv run-full.log $? &&
    { no_partial limited trace.csv && json_ok limited/summary.json &&
        ok "run, trace over the size limit: exit 2, no partial trace, summary complete" ||
        fail "run: a partial trace.csv is left or summary.json is incomplete"; }
  (ulimit -f 8; "$vmt" snapshot "$jog" --at 0.1 --out limited/shot.png) >shot-full.log 2>&1
  expect_write_error "snapshot over the size limit" shot.png shot-full.log $? &&
    { no_partial limited shot.png && ok "snapshot over the size limit: exit 2, no partial PNG" ||
        fail "snapshot: a partial PNG is left"; }
  mkdir -p served
  (ulimit -f 1; "$vmt" serve "$jog" --modbus 127.0.0.1:0 --idle-timeout 1 --out served) \
    >serve-full.log 2>&1
  expect_write_error "serve over the size limit" "(events.jsonl|summary.json)" serve-full.log $? &&
    ok "serve over the size limit: exit 2, each lost file named"
fi
# A streamed file on a full device: events.jsonl is written as the run goes.
mkdir -p devfull && ln -sf /dev/full devfull/events.jsonl
"$vmt" run "$jog" --out devfull >devfull.log 2>&1
expect_write_error "run, events.jsonl on /dev/full" events.jsonl devfull.log $? &&
  { json_ok devfull/summary.json && [ -s devfull/trace.csv ] &&
      ok "run, events.jsonl on /dev/full: exit 2, trace and summary complete" ||
      fail "run: the other files were lost with events.jsonl"; }

# --- SIGTERM and SIGINT stop vmt run at the next tick -------------------------------------
for sig in TERM INT; do
  "$vmt" run "$jog" --until 300 --out "sig$sig" >"sig$sig.log" 2>&1 &
  pid=$!
  # Signalled once the run's ticks go (its first event is written): a signal before vmt catches
  # it is ignored by a background job of this shell (SIGINT) or ends it outright (SIGTERM).
  for _ in $(seq 1 600); do [ -s "sig$sig/events.jsonl" ] && break; sleep 0.1; done
  sleep 0.3
  kill -"$sig" "$pid"
  wait "$pid"
  code=$?
  s=sig$sig/summary.json
  if [ "$code" != 3 ]; then fail "SIG$sig: exit $code, wanted 3"; sed 's/^/    /' "sig$sig.log" | tail -3
  elif ! json_ok "$s"; then fail "SIG$sig: summary.json is not complete JSON"
  elif ! python3 -c "import json,sys; s=json.load(open(sys.argv[1]))
assert s['stopped_early'] is True and s['stop_reason'] == 'SIG$sig'
assert 0 < s['simulated_time_s'] < 300" "$s"; then fail "SIG$sig: summary.json says no stop and when"
  elif ! jsonl_ok "sig$sig/events.jsonl"; then fail "SIG$sig: events.jsonl has a cut line"
  elif [ "$(tail -c 1 "sig$sig/trace.csv" | od -An -c | tr -d ' ')" != '\n' ]; then
    fail "SIG$sig: trace.csv ends mid-row"
  elif ! grep -q "stopped early at .*SIG$sig" "sig$sig.log"; then fail "SIG$sig: no message"
  else ok "SIG$sig: exit 3, complete files, summary says stopped at $(grep -o '"simulated_time_s": [0-9.]*' "$s")"
  fi
done

# --- A killed study takes its workers with it ----------------------------------------------
"$vmt" study repos "$study" --every-ms 20 --jobs 2 --snapshots 0 --out killed >killed.log 2>&1 &
pid=$!
workers=""
for _ in $(seq 1 300); do  # the reference run first, then the workers fork
  workers=$(pgrep -P "$pid" | tr '\n' ' ')
  [ -n "$workers" ] && break
  sleep 0.1
done
if [ -z "$workers" ]; then
  fail "study kill: no worker process seen"; kill -9 "$pid"
else
  sleep 0.5
  family=$workers
  for w in $workers; do family="$family $(pgrep -P "$w" | tr '\n' ' ')"; done
  kill -9 "$pid"
  wait "$pid" 2>/dev/null
  left=$family
  for _ in $(seq 1 50); do
    left=""
    for p in $family; do kill -0 "$p" 2>/dev/null && left="$left $p"; done
    [ -z "$left" ] && break
    sleep 0.1
  done
  if [ -n "$left" ]; then
    fail "study kill: processes outlive the killed study:$left"
    for p in $left; do kill -9 "$p" 2>/dev/null; done
  else ok "study kill -9: its $(echo $family | wc -w) worker processes end with it"; fi
fi

# What the killed study left (its scratch folder, a temporary) goes with the next run there.
mkdir -p killed/.reference-999999999 && touch killed/cases.jsonl.tmp-999999999
"$vmt" study repos "$study" --max-cases 1 --snapshots 0 --out killed >rerun.log 2>&1 ||
  fail "study rerun after a kill: $(tail -3 rerun.log)"
if ls -a killed | grep -qE '^\.reference-|\.tmp-'; then
  fail "study rerun left what the killed study left: $(ls -a killed | tr '\n' ' ')"
else ok "study rerun after kill -9: the dead study's scratch folder and temporaries are gone"; fi

# --- study merge of a corrupt cases.jsonl --------------------------------------------------
mkdir -p corrupt
printf '{"case":"a","verdict":"clear"}\nnot json at all\n[1,2]\n{"case":"b"' >corrupt/cases.jsonl
"$vmt" study merge corrupt --out merged >merge.log 2>&1
code=$?
if [ "$code" != 2 ]; then fail "merge of a corrupt cases.jsonl: exit $code, wanted 2"; cat merge.log
elif ! grep -q 'corrupt/cases.jsonl:2: not JSON' merge.log ||
  ! grep -q 'corrupt/cases.jsonl:3: not a JSON object' merge.log ||
  ! grep -q 'corrupt/cases.jsonl:4: the last line is cut short' merge.log; then
  fail "merge of a corrupt cases.jsonl: the bad lines are not named"; cat merge.log
elif [ -e merged/cases.jsonl ]; then fail "merge of a corrupt cases.jsonl wrote cases.jsonl"
else ok "study merge of a corrupt cases.jsonl: exit 2, each bad line named"; fi

[ "$fails" = 0 ] || { echo "$fails failure(s)"; exit 1; }
echo "all passed"
