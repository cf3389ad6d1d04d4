#!/usr/bin/env bash
# vmt serve --http, the operator station, as a user and a careless client meet it: the page and
# its JSON API, keys and run control, bad requests answered 4xx with nothing changed, five pages
# at once seeing one state, the token off loopback, an external PLC keeping the clock, and the
# operator's inputs replayed by vmt run --operator to the same digest. With chromium and
# chromedriver installed, a real browser drives the page (tests/station/station_page.py).
# Usage: station_test.sh VMT SRC OUT
set -u
vmt=$1 src=$2 out=$3
rm -rf "$out" && mkdir -p "$out"
fails=0
fail() { echo "FAIL $*"; fails=$((fails+1)); }
python=/usr/bin/python3
scene=$src/scenes/machine-panel.yaml
station_scene=$src/scenes/station.yaml

start_station() {  # start_station OUTDIR [SCENE [OPTION...]]: sets pid and port
  local dir=$1 what=${2:-$scene}
  shift $(($# < 2 ? $# : 2))
  mkdir -p "$dir"
  timeout 600 "$vmt" serve "$what" --http 127.0.0.1:0 --out "$dir" "$@" >"$dir/serve.log" 2>&1 &
  pid=$!
  station_port "$dir/serve.log"
}
station_port() {  # station_port LOG: waits for the station's address in LOG; sets port
  for _ in $(seq 1200); do
    port=$(sed -n 's|.*operator station on http://[0-9.]*:\([0-9]*\)/.*|\1|p' "$1")
    [ -n "$port" ] && return 0
    sleep 0.05
  done
  fail "the station did not start: $(cat "$1")"; return 1
}
url() { echo "http://127.0.0.1:$port$1"; }
status() {  # status EXPECTED METHOD PATH [BODY]
  local want=$1 method=$2 path=$3 body=${4-}
  local got
  if [ "$method" = GET ]; then
    got=$(curl -s -o "$out/last.json" -w '%{http_code}' "$(url "$path")")
  else
    got=$(curl -s -o "$out/last.json" -w '%{http_code}' -X "$method" --data-binary "$body" \
          -H 'Content-Type: application/json' "$(url "$path")")
  fi
  [ "$got" = "$want" ] || fail "$method $path $body: HTTP $got, expected $want ($(head -c 200 "$out/last.json"))"
}
state() {  # state EXPR: the Python expression holds for /api/state's `d`
  curl -s "$(url /api/state)" | "$python" -c 'import json, sys
d = json.load(sys.stdin)
sys.exit(0 if eval(sys.argv[1]) else 1)' "$1"
}
wait_state() {  # wait_state EXPR SECONDS
  for _ in $(seq $(($2 * 20))); do state "$1" && return 0; sleep 0.05; done
  fail "state never showed $1"; return 1
}

# --- The page and its API, paced by the page (lockstep, starts paused).
start_station "$out/live" || exit 1
status 200 GET /
grep -q 'data-view="machine"' "$out/last.json" || fail "the page has no 3D view canvas"
status 200 GET /vendor/three/build/three.module.js
status 200 GET /api/model
"$python" - "$out/last.json" <<'PY' || fail "/api/model lacks links, keys or axes"
import json, sys
m = json.load(open(sys.argv[1]))
assert m["scene"] == "machine-panel" and len(m["links"]) > 5
assert "mJGPOS_X" in m["keys"] and m["axes"][0]["name"] == "X" and m["program"]["lines"]
PY
wait_state 'd["run"] == "paused" and d["t"] == 0' 5
for i in 1 2 3 4 5; do status 200 POST /api/run '{"action":"step"}'; done
wait_state 'd["cycle"] == 5 and d["run"] == "paused"' 10
# Five pages at once see one state.
pages=()
for i in 1 2 3 4 5; do curl -s "$(url /api/state)" >"$out/page$i.json" & pages+=($!); done
wait "${pages[@]}"
for i in 2 3 4 5; do cmp -s "$out/page1.json" "$out/page$i.json" || fail "page $i saw another state"; done
status 200 POST /api/key '{"name":"mCOOLANT","pressed":true}'
status 200 POST /api/run '{"action":"step"}'
status 200 POST /api/key '{"name":"mCOOLANT","pressed":false}'
status 200 POST /api/run '{"action":"step"}'
wait_state 'd["cycle"] == 7' 10
# The handwheel: taken like a key, recorded, replayed (the channel moves only in handwheel mode).
status 200 POST /api/handwheel '{"axis":"X","counts":5}'
status 404 POST /api/handwheel '{"axis":"Q","counts":5}'
status 400 POST /api/handwheel '{"axis":"X","counts":0}'
status 400 POST /api/handwheel '{"axis":"X","counts":1.5}'
status 200 POST /api/run '{"action":"step"}'
wait_state 'd["cycle"] == 8' 10
# The feed override switch (a selector): set to one of its positions, the PLC makes it PxxC.FOVR.
status 200 POST /api/signal '{"name":"mFOVR","value":50}'
status 403 POST /api/signal '{"name":"mFOVR","value":77}'
status 404 POST /api/key '{"name":"mFOVR","pressed":true}'
status 200 POST /api/run '{"action":"step"}'
status 200 POST /api/run '{"action":"step"}'
wait_state 'd["cycle"] == 10 and d["selectors"]["mFOVR"] == 50 and d["nc"]["override"]["feed"] == 0.5' 10
status 200 POST /api/signal '{"name":"mFOVR","value":100}'  # back, for the scene's timing
status 200 POST /api/run '{"action":"step"}'
wait_state 'd["cycle"] == 11 and d["selectors"]["mFOVR"] == 100' 10
# events.jsonl grows as the run goes (a PLC engineer follows it with tail -f), not at its end.
grep -q '"signal":"mFOVR","value":50' "$out/live/events.jsonl" ||
  fail "events.jsonl is not written as the run goes: $(wc -l < "$out/live/events.jsonl") lines"
# Bad requests: 4xx, and nothing queued.
status 400 POST /api/key 'not json'
status 400 POST /api/key '{"name":"mCOOLANT"}'
status 404 POST /api/key '{"name":"mNOKEY","pressed":true}'
status 403 POST /api/signal '{"name":"P00S.RUN","value":1}'
status 403 POST /api/signal '{"name":"P00C.SBL","value":1}'
status 404 POST /api/signal '{"name":"NO.SUCH","value":1}'
status 403 POST /api/signal '{"name":"mAUTO","value":7}'
status 400 POST /api/run '{"action":"fly"}'
status 400 POST /api/run '{"action":"run","speed":-1}'
status 400 GET '/api/events?from=-3'
status 404 GET /api/nothing
status 404 GET '/../../etc/passwd'
big=$(head -c 100000 /dev/zero | tr '\0' a)
status 413 POST /api/key "{\"name\":\"$big\",\"pressed\":true}"
status 200 GET '/api/events?from=0'
"$python" -c 'import json,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if any(e.get("event")=="operator" for e in d["events"]) else 1)' \
  "$out/last.json" || fail "the key presses are not in the event log"
# Run to the end as fast as the machine allows; the station stays up showing it.
status 200 POST /api/run '{"action":"run","speed":0}'
wait_state 'd["run"] == "ended"' 120
status 200 GET /api/signals
kill -INT $pid; wait $pid; rc=$?
[ $rc = 0 ] || fail "vmt serve --http exited $rc after the scene's end and SIGINT"
grep -c mCOOLANT "$out/live/operator.yaml" | grep -q 2 || fail "operator.yaml lacks the two key changes"
grep -q 'handwheel: "X", counts: 5' "$out/live/operator.yaml" || fail "operator.yaml lacks the handwheel"
grep -q 'signal: "mFOVR", value: 50' "$out/live/operator.yaml" || fail "operator.yaml lacks the override switch"
live=$("$python" -c 'import json,sys; print(json.load(open(sys.argv[1]))["trace_digest"])' "$out/live/serve.json")
"$vmt" run "$scene" --operator "$out/live/operator.yaml" --out "$out/replay" >"$out/replay.log" 2>&1 ||
  fail "the replay failed: $(cat "$out/replay.log")"
grep -q "trace digest $live" "$out/replay.log" || fail "the replay's digest differs from the live run's $live"
cmp -s "$out/live/events.jsonl" "$out/replay/events.jsonl" || fail "the replay's events differ"

# --- A quick click while paused: the press is taken now, the release a PLC cycle later, so
# that the PLC sees the key.
start_station "$out/click" "$station_scene" || exit 1
status 200 POST /api/key '{"name":"mCOOLANT","pressed":true}'
status 200 POST /api/key '{"name":"mCOOLANT","pressed":false}'
status 200 POST /api/run '{"action":"step"}'
status 200 POST /api/run '{"action":"step"}'
wait_state 'd["cycle"] == 2' 10
kill -TERM $pid; wait $pid
grep -q 'tick: 0, signal: "mCOOLANT", value: 1' "$out/click/operator.yaml" &&
  grep -q 'tick: 16, signal: "mCOOLANT", value: 0' "$out/click/operator.yaml" ||
  fail "a quick click was not taken a PLC cycle apart: $(cat "$out/click/operator.yaml")"

# --- A real browser on the page (headless chromium through chromedriver).
if [ -x /usr/bin/chromedriver ] && "$python" -c 'import selenium' 2>/dev/null; then
  # The scene with nothing scripted: the page's keys alone operate the machine. Its 3D view at
  # t = 0 against a golden; VMT_REFRESH_STATION_GOLDEN=1 writes the golden instead.
  start_station "$out/browser" "$station_scene" || exit 1
  timeout 300 "$python" "$src/tests/station/station_page.py" --url "$(url /)" \
    --screenshot "$out/browser/canvas.png" --jog-key mJGPOS_X --jog-axis X --manual-key mMANU \
    --auto-key mAUTO --start-key mSTART --vmt "$vmt" \
    --golden "$src/tests/golden/station-page/canvas.png" --golden-out "$out/browser/golden" \
    ${VMT_REFRESH_STATION_GOLDEN:+--refresh-golden} >"$out/browser/page.log" 2>&1 ||
    fail "the page in chromium: $(tail -8 "$out/browser/page.log")"
  kill -INT $pid; wait $pid
else
  echo "skipped: no chromium-driver / python3-selenium (tools/setup-debian.sh installs them)"
fi

# --- vmt view: the recorded run again, at any time; watched, not operated.
timeout 600 "$vmt" view "$out/live" --http 127.0.0.1:0 >"$out/view.log" 2>&1 &
pid=$!
station_port "$out/view.log"
status 200 GET /api/model
grep -q '"pace":"replay"' "$out/last.json" || fail "vmt view's model is not a replay"
status 200 POST /api/run '{"action":"seek","t":10.5}'
wait_state 'abs(d["t"] - 10.5) < 1e-9 and d["nc"]["state"] == "ended" and d["run"] == "paused"' 30
status 200 POST /api/run '{"action":"seek","t":1.5}'
wait_state 'abs(d["t"] - 1.5) < 1e-9 and d["nc"]["state"] == "running"' 30
# The functions' panels: the REPOS screen, the headstock with its PLC signals, block search.
wait_state 'd["repos"]["function"] == "none" and d["headstock"]["mode"] == "spindle" and "A03.SPMOD_Q" in d["headstock"]["signals"] and d["block_search"]["state"].startswith("HLI_BS_")' 10
status 403 POST /api/key '{"name":"mAUTO","pressed":true}'
status 400 POST /api/run '{"action":"seek","t":-1}'
status 200 POST /api/run '{"action":"run","speed":0}'
wait_state 'd["run"] == "ended"' 60
if [ -x /usr/bin/chromedriver ] && "$python" -c 'import selenium' 2>/dev/null; then
  timeout 300 "$python" "$src/tests/station/station_page.py" --url "$(url /)" \
    --screenshot "$out/view-canvas.png" --seek 3.25 >"$out/view-page.log" 2>&1 ||
    fail "vmt view's page in chromium: $(tail -5 "$out/view-page.log")"
fi
kill -INT $pid; wait $pid
grep -q "differs from the recorded" "$out/view.log" && fail "the replay's digest differs: $(cat "$out/view.log")"
status_missing=$("$vmt" view "$out/nothing-here" --http 127.0.0.1:0 2>&1)
[ $? = 2 ] && echo "$status_missing" | grep -q "no summary.json" ||
  fail "vmt view of a folder without a run: $status_missing"

# --- Off loopback only with a token, and then every request carries it.
"$vmt" serve "$scene" --http 0.0.0.0:0 --out "$out/open" >"$out/open.log" 2>&1
[ $? = 2 ] && grep -q "needs --http-token" "$out/open.log" || fail "a non-loopback address without a token was not refused"
timeout 600 "$vmt" serve "$scene" --http 0.0.0.0:0 --http-token s3cret --out "$out/token" \
  >"$out/token.log" 2>&1 &
pid=$!
station_port "$out/token.log"
status 401 GET /api/state
code=$(curl -s -o /dev/null -w '%{http_code}' -H 'Authorization: Bearer s3cret' "$(url /api/state)")
[ "$code" = 200 ] || fail "the token was not accepted ($code)"
code=$(curl -s -o /dev/null -w '%{http_code}' "$(url '/?token=s3cret')")
[ "$code" = 200 ] || fail "the page with ?token= was not served ($code)"
kill -TERM $pid; wait $pid

# --- With an external PLC over Modbus the PLC keeps the clock: the page cannot pause it.
timeout 600 "$vmt" serve "$scene" --http 127.0.0.1:0 --modbus 127.0.0.1:0 --idle-timeout 60 \
  --out "$out/modbus" >"$out/modbus.log" 2>&1 &
pid=$!
station_port "$out/modbus.log"
grep -q "Modbus TCP on" "$out/modbus.log" || fail "--modbus with --http did not serve Modbus"
status 409 POST /api/run '{"action":"pause"}'
status 200 GET /api/state
kill -TERM $pid; wait $pid

echo "station: $fails failed"
[ $fails = 0 ]
