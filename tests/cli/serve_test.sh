#!/usr/bin/env bash
# vmt serve with an external PLC: the Python example PLC steps the scene in lockstep over Modbus
# TCP and must give the same run as the same program embedded (trace digest and every gateway
# signal change); mbpoll reads the status as any Modbus tool would; a bad write gets an
# exception. Usage: serve_test.sh VMT SRC OUT
set -u
vmt=$1 src=$2 out=$3
rm -rf "$out" && mkdir -p "$out"
fails=0
fail() { echo "FAIL $*"; fails=$((fails+1)); }
python=/usr/bin/python3  # Debian's, with python3-pymodbus
scene=$src/scenes/repos-machine-keys.yaml

# Start vmt serve on a free port; prints the port it listens on.
start_serve() {  # start_serve OUTDIR MODE
  mkdir -p "$1"
  "$vmt" serve "$scene" --modbus 127.0.0.1:0 "--$2" --out "$1" >"$1/serve.log" 2>&1 &
  serve_pid=$!
  for _ in $(seq 100); do
    port=$(sed -n 's/.*Modbus TCP on 127.0.0.1:\([0-9]*\).*/\1/p' "$1/serve.log")
    [ -n "$port" ] && return 0
    sleep 0.05
  done
  fail "vmt serve did not start"; cat "$1/serve.log"; return 1
}

"$vmt" signals "$src/models/lathe-c1/machine.yaml" --format json >"$out/signals.json" ||
  fail "vmt signals"
"$vmt" run "$scene" --out "$out/embedded" >"$out/embedded.log" 2>&1 || fail "embedded run"

# Lockstep: the external PLC drives the whole scene.
if start_serve "$out/external" lockstep; then
  timeout 120 "$python" "$src/examples/plc/repos_machine_keys.py" --port "$port" \
    --signals "$out/signals.json" >"$out/client.log" 2>&1 || { fail "python PLC"; cat "$out/client.log"; }
  wait $serve_pid || { fail "vmt serve exit $?"; cat "$out/external/serve.log"; }
  d1=$(grep -o '"trace_digest": "[0-9a-f]*"' "$out/embedded/summary.json")
  d2=$(grep -o '"trace_digest": "[0-9a-f]*"' "$out/external/summary.json")
  [ -n "$d1" ] && [ "$d1" = "$d2" ] || fail "trace digest embedded $d1 vs external $d2"
  grep '"signal"' "$out/embedded/events.jsonl" >"$out/embedded.signals"
  grep '"signal"' "$out/external/events.jsonl" >"$out/external.signals"
  cmp -s "$out/embedded.signals" "$out/external.signals" ||
    { fail "signal changes differ"; diff "$out/embedded.signals" "$out/external.signals" | head; }
  grep -q '"passed": true' "$out/external/summary.json" || fail "external run's expectations"
  grep -q '"expectations_failed": 0' "$out/external/summary.json" || fail "external expectations failed"
fi

# Lockstep with a PLC that drives valves and acknowledges M functions: the panel program in
# Python gives the embedded machine_panel's run, byte for byte.
scene=$src/scenes/machine-panel.yaml
"$vmt" run "$scene" --out "$out/panel_embedded" >"$out/panel_embedded.log" 2>&1 || fail "embedded panel run"
if start_serve "$out/panel_external" lockstep; then
  timeout 120 "$python" "$src/examples/plc/machine_panel.py" --port "$port" \
    --signals "$out/signals.json" >"$out/panel_client.log" 2>&1 || { fail "python panel PLC"; cat "$out/panel_client.log"; }
  wait $serve_pid || { fail "vmt serve (panel) exit $?"; cat "$out/panel_external/serve.log"; }
  d1=$(grep -o '"trace_digest": "[0-9a-f]*"' "$out/panel_embedded/summary.json")
  d2=$(grep -o '"trace_digest": "[0-9a-f]*"' "$out/panel_external/summary.json")
  [ -n "$d1" ] && [ "$d1" = "$d2" ] || fail "panel trace digest embedded $d1 vs external $d2"
  grep '"signal"' "$out/panel_embedded/events.jsonl" >"$out/panel_embedded.signals"
  grep '"signal"' "$out/panel_external/events.jsonl" >"$out/panel_external.signals"
  cmp -s "$out/panel_embedded.signals" "$out/panel_external.signals" ||
    { fail "panel signal changes differ"; diff "$out/panel_embedded.signals" "$out/panel_external.signals" | head; }
  grep -q '"expectations_failed": 0' "$out/panel_external/summary.json" || fail "external panel expectations failed"
fi
scene=$src/scenes/repos-machine-keys.yaml

# mbpoll reads the status, and writing an NC status address is refused.
if start_serve "$out/mbpoll" lockstep; then
  addr=$("$python" -c "import json,sys; d=json.load(open(sys.argv[1])); print([s['modbus']['address'] for s in d['signals'] if s['name']=='P00S.RUN'][0])" "$out/signals.json")
  # mbpoll counts references from 1 unless -0; -t 1 discrete inputs, one poll.
  mbpoll -m tcp -a 1 -p "$port" -0 -t 1 -r "$addr" -c 1 -1 127.0.0.1 >"$out/mbpoll.log" 2>&1 ||
    fail "mbpoll read"
  grep -qE "^\[$addr\]:[[:space:]]+0" "$out/mbpoll.log" || { fail "mbpoll output"; cat "$out/mbpoll.log"; }
  # A holding register no signal owns (past the cycle register): exception 02.
  cyc=$("$python" -c "import json,sys; print(json.load(open(sys.argv[1]))['modbus']['lockstep_cycle_register'])" "$out/signals.json")
  mbpoll -m tcp -a 1 -p "$port" -0 -t 4 -r $((cyc + 1)) -1 127.0.0.1 7 >"$out/mbpoll_write.log" 2>&1 &&
    fail "mbpoll write past the map succeeded"
  grep -qi "illegal data address" "$out/mbpoll_write.log" || { fail "no exception 02"; cat "$out/mbpoll_write.log"; }
  kill $serve_pid; wait $serve_pid 2>/dev/null
  grep -q '"stopped_early": true' "$out/mbpoll/serve.json" || fail "serve.json after SIGTERM"
fi

[ $fails = 0 ] && echo "serve test: all passed" || echo "serve test: $fails failed"
exit $((fails > 0))
