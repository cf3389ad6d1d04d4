#!/usr/bin/env bash
# vmt serve with an external PLC: the Python example PLC steps the scene in lockstep over Modbus
# TCP and must give the same run as the same program embedded (trace digest and every gateway
# signal change); mbpoll reads the status as any Modbus tool would; a bad write gets an
# exception; AXD_WR writes a drive parameter through the AXD_WR block. A PLC that goes away: in real time the link watchdog stops the NC (and stays quiet
# while a client polls), in lockstep the idle timeout ends serve, and the client_gone fault
# drops the clients. Timeouts are generous: no assert depends on the machine being fast.
# Usage: serve_test.sh VMT SRC OUT
set -u
vmt=$1 src=$2 out=$3
rm -rf "$out" && mkdir -p "$out"
fails=0
fail() { echo "FAIL $*"; fails=$((fails+1)); }
python=/usr/bin/python3  # Debian's, with python3-pymodbus
scene=$src/scenes/repos-machine-keys.yaml

# Start vmt serve on a free port; prints the port it listens on.
start_serve() {  # start_serve OUTDIR MODE [SCENE [OPTION...]]
  local dir=$1 mode=$2 what=${3:-$scene}
  shift $(($# < 3 ? $# : 3))
  mkdir -p "$dir"
  timeout 300 "$vmt" serve "$what" --modbus 127.0.0.1:0 "--$mode" --out "$dir" "$@" \
    >"$dir/serve.log" 2>&1 &
  serve_pid=$!  # timeout's, which passes signals on and exits with serve's status
  for _ in $(seq 1200); do
    port=$(sed -n 's/.*Modbus TCP on 127.0.0.1:\([0-9]*\).*/\1/p' "$dir/serve.log")
    [ -n "$port" ] && return 0
    sleep 0.05
  done
  fail "vmt serve did not start"; cat "$dir/serve.log"; return 1
}

# json FILE EXPR: fails the test unless the Python expression EXPR holds for the file's data `d`.
json() {
  "$python" -c 'import json, sys
d = json.load(open(sys.argv[1]))
sys.exit(0 if eval(sys.argv[2]) else 1)' "$1" "$2" || fail "$1: $2"
}

"$vmt" signals "$src/models/lathe-c1/machine.yaml" --format json >"$out/signals.json" ||
  fail "vmt signals"
# same_as_embedded NAME SCENE PLC [OPTION...]: the scene run embedded, then served in lockstep to
# the example PLC `PLC` (with OPTIONs): the two runs must be the same (trace digest and every
# gateway signal change) and the served run's expectations hold. Runs land in $out/NAME_*.
same_as_embedded() {
  local name=$1 what=$2 plc=$3
  shift 3
  "$vmt" run "$what" --out "$out/${name}_embedded" >"$out/${name}_embedded.log" 2>&1 ||
    fail "$name: embedded run"
  start_serve "$out/${name}_external" lockstep "$what" || return 1
  timeout 120 "$python" "$src/examples/plc/$plc" --port "$port" --signals "$out/signals.json" \
    "$@" >"$out/${name}_client.log" 2>&1 || { fail "$name: $plc"; cat "$out/${name}_client.log"; }
  wait $serve_pid || { fail "$name: vmt serve exit $?"; cat "$out/${name}_external/serve.log"; }
  local d1 d2
  d1=$(grep -o '"trace_digest": "[0-9a-f]*"' "$out/${name}_embedded/summary.json")
  d2=$(grep -o '"trace_digest": "[0-9a-f]*"' "$out/${name}_external/summary.json")
  [ -n "$d1" ] && [ "$d1" = "$d2" ] || fail "$name: trace digest embedded $d1 vs external $d2"
  for run in embedded external; do
    grep '"signal"' "$out/${name}_$run/events.jsonl" >"$out/${name}_$run.signals"
  done
  cmp -s "$out/${name}_embedded.signals" "$out/${name}_external.signals" ||
    { fail "$name: signal changes differ"; diff "$out/${name}_embedded.signals" "$out/${name}_external.signals" | head; }
  grep -q '"expectations_failed": 0' "$out/${name}_external/summary.json" ||
    fail "$name: external run's expectations failed"
}

# The machine-key program (8.2) drives the whole scene.
same_as_embedded keys "$scene" repos_machine_keys.py &&
  { grep -q '"passed": true' "$out/keys_external/summary.json" || fail "keys: external run failed"; }
# A PLC that drives valves and acknowledges M functions: the panel program.
same_as_embedded panel "$src/scenes/machine-panel.yaml" machine_panel.py
# The same PLC holding AUXACK until AUXSTB falls (a four-phase handshake) instead of pulsing it:
# the NC holds each phase a scan, so it sees every edge and the run is the same.
same_as_embedded panel_hold "$src/scenes/machine-panel.yaml" machine_panel.py --hold-ack
# The C-axis changeover (4.4) over Modbus: the Python program takes the place of the one the
# runner runs for a scene without plc:, writes the AXD idents (DINT registers) and switches the
# clutch.
same_as_embedded cax "$src/scenes/c-axis-switching.yaml" c_axis_changeover.py
# The wrong C-axis changeover PLC (--wrong: ROTMOD_Q before the clutch meshed) gives the
# embedded wrong variant's run, and so its NC error (504, C's following error).
if same_as_embedded wrong "$src/scenes/fault-changeover-wrong-plc.yaml" c_axis_changeover.py \
  --wrong; then
  for run in wrong_embedded wrong_external; do
    grep -q '"name":"P00S.ERRNR","value":504.0' "$out/$run/events.jsonl" || fail "$run: no message 504"
    grep -q '"state":"error","error":"axis C: following error beyond its limit"' \
      "$out/$run/events.jsonl" || fail "$run: no following error of C"
  done
fi

# The minimal PLC of docs/plc.md (standard library only) drives a program to its end: automatic
# mode, cycle start, M functions acknowledged four-phase (M08 on the coolant pressure), spindle
# mode. It reads the NC status block (input registers) over the wire: X moves from 150 to 40.
if start_serve "$out/minimal" lockstep "$src/examples/plc/minimal_plc.yaml"; then
  timeout 120 "$python" "$src/examples/plc/minimal_plc.py" --port "$port" \
    --signals "$out/signals.json" >"$out/minimal/client.log" 2>&1 ||
    { fail "minimal_plc.py: exit $?"; cat "$out/minimal/client.log"; }
  wait $serve_pid || { fail "minimal: vmt serve exit $?"; cat "$out/minimal/serve.log"; }
  grep -q "NC status block at input register 1000" "$out/minimal/serve.log" ||
    fail "serve names no NC status block"
  grep -q "program ended" "$out/minimal/client.log" || fail "minimal: the program did not end"
  grep -q "NC running" "$out/minimal/client.log" || fail "minimal: NC.STATE never showed running"
  grep -q "axis X (A01): 150.0000 -> 40.0000 \[mm\]" "$out/minimal/client.log" ||
    { fail "minimal: X not read moving from 150 to 40"; cat "$out/minimal/client.log"; }
  json "$out/minimal/summary.json" 'd["expectations_failed"] == 0 and d["expectations_passed"] == 4'
fi
# The same PLC in real time for 2 s: the clock waits for its first write, the status block is
# refreshed as the wall clock runs, and it reads X leaving 150 mm (the watchdog generous: the
# assert is about the block, not about how fast this machine scans).
rt=$out/minimal-realtime
mkdir -p "$rt"
timeout 300 "$vmt" serve "$src/examples/plc/minimal_plc.yaml" --modbus 127.0.0.1:0 --realtime \
  --until 2 --plc-timeout 2000 --out "$rt" >"$rt/serve.log" 2>&1 &
serve_pid=$!
mb_port=
for _ in $(seq 1200); do
  mb_port=$(sed -n 's/.*Modbus TCP on 127.0.0.1:\([0-9]*\),.*/\1/p' "$rt/serve.log")
  [ -n "$mb_port" ] && break
  sleep 0.05
done
timeout 120 "$python" "$src/examples/plc/minimal_plc.py" --port "$mb_port" --realtime \
  --signals "$out/signals.json" >"$rt/client.log" 2>&1  # 1: the program has not ended at 2 s
wait $serve_pid
grep -q "NC running" "$rt/client.log" || { fail "minimal realtime: never running"; cat "$rt/client.log"; }
"$python" - "$rt/client.log" <<'PY' || { fail "minimal realtime: X did not move"; cat "$rt/client.log"; }
import re, sys
m = re.search(r"axis X \(A01\): ([-0-9.]+) -> ([-0-9.]+)", open(sys.argv[1]).read())
sys.exit(0 if m and float(m.group(1)) == 150 and float(m.group(2)) < 100 else 1)
PY
json "$rt/serve.json" 'd["mode"] == "realtime" and d["plc_link"]["lost"] == 0'

scene=$src/scenes/repos-machine-keys.yaml

# mbpoll reads the status, and writing an NC status address is refused.
if start_serve "$out/mbpoll" lockstep; then
  addr=$("$python" -c "import json,sys; d=json.load(open(sys.argv[1])); print([s['modbus']['address'] for s in d['signals'] if s['name']=='P00S.RUN'][0])" "$out/signals.json")
  # mbpoll counts references from 1 unless -0; -t 1 discrete inputs, one poll.
  mbpoll -m tcp -a 1 -p "$port" -0 -t 1 -r "$addr" -c 1 -1 127.0.0.1 >"$out/mbpoll.log" 2>&1 ||
    fail "mbpoll read"
  grep -qE "^\[$addr\]:[[:space:]]+0" "$out/mbpoll.log" || { fail "mbpoll output"; cat "$out/mbpoll.log"; }
  # The NC status block with function 04 (-t 3): layout version 1, four axis rows.
  mbpoll -m tcp -a 1 -p "$port" -0 -t 3 -r 1000 -c 2 -1 127.0.0.1 >"$out/mbpoll_status.log" 2>&1 ||
    fail "mbpoll read of the NC status block"
  grep -qE "^\[1000\]:[[:space:]]+1$" "$out/mbpoll_status.log" &&
    grep -qE "^\[1001\]:[[:space:]]+4$" "$out/mbpoll_status.log" ||
    { fail "mbpoll NC status output"; cat "$out/mbpoll_status.log"; }
  # A holding register no signal owns (past the cycle register and the AXD_WR block): 02.
  cyc=$("$python" -c "import json,sys; print(json.load(open(sys.argv[1]))['modbus']['lockstep_cycle_register'])" "$out/signals.json")
  mbpoll -m tcp -a 1 -p "$port" -0 -t 4 -r $((cyc + 7)) -1 127.0.0.1 7 >"$out/mbpoll_write.log" 2>&1 &&
    fail "mbpoll write past the map succeeded"
  grep -qi "illegal data address" "$out/mbpoll_write.log" || { fail "no exception 02"; cat "$out/mbpoll_write.log"; }
  kill $serve_pid; wait $serve_pid; rc=$?
  [ $rc = 3 ] || fail "serve after SIGTERM: exit $rc, not 3"
  json "$out/mbpoll/serve.json" 'd["stopped_early"] and d["stop_reason"] == "signal"'
fi

# AXD_WR over Modbus (fast-measurement 7.2): an external PLC writes a measuring drive's probe
# parameters through serve's AXD_WR block, the path the embedded probe block's AXD_WR takes; the
# drive's answer reads back (done, refused, no axis) and a bad request is exception 03.
if start_serve "$out/axd" lockstep "$src/scenes/measure-shaft.yaml"; then
  PYTHONPATH="$src/examples/plc" "$python" - "$port" "$out/signals.json" >"$out/axd.log" 2>&1 <<'PY' ||
import json, sys
from pymodbus.client import ModbusTcpClient
from vmt_modbus import Gateway
client = ModbusTcpClient("127.0.0.1", port=int(sys.argv[1]))
assert client.connect()
signals = json.load(open(sys.argv[2]))
io = Gateway(client, signals)
b = io.axd_wr_register
assert b == signals["modbus"]["lockstep_cycle_register"] + 1, b
assert io.axd_wr(1, 303, 405) == "done"      # S-0-0303: real-time control bit 2 = probe 1 enable
assert io.axd_wr(1, 170, 1) == "done"        # S-0-0170: probe 1, positive edge
assert io.axd_wr(1, 170, 9) == "refused"     # not a probe control word
assert io.axd_wr(1, 999, 1) == "refused"     # a parameter the drive does not have
assert io.axd_wr(32, 170, 1) == "no axis"
r = client.read_holding_registers(b, 6, slave=1)
assert list(r.registers) == [32, 170, 0, 1, 2, 5], r.registers
r = client.write_registers(b, [0, 170, 0, 1], slave=1)          # axis 0
assert r.isError() and r.exception_code == 3, r
r = client.write_register(b, 1, slave=1)                         # part of the block
assert r.isError() and r.exception_code == 2, r
assert list(client.read_holding_registers(b + 4, 2, slave=1).registers) == [2, 5]
print("AXD_WR over Modbus: ok")
PY
    { fail "AXD_WR over Modbus"; cat "$out/axd.log"; }
  grep -q "AXD_WR block at holding register" "$out/axd/serve.log" || fail "serve names no AXD_WR block"
  kill $serve_pid; wait $serve_pid
fi

# The example PLC, started before serve on a free port and connecting as soon as serve listens
# (with --retry): imported and ready, it is there from serve's first cycle on.
start_client() {  # start_client DIR OPTION...; sets port and client_pid
  local dir=$1
  shift
  mkdir -p "$dir"
  port=$("$python" -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
  timeout 300 "$python" "$src/examples/plc/repos_machine_keys.py" --port "$port" --retry 120 \
    --signals "$out/signals.json" "$@" >"$dir/client.log" 2>&1 &
  client_pid=$!
  for _ in $(seq 1200); do grep -q connecting "$dir/client.log" && break; sleep 0.05; done
}

# Real time with an external PLC that polls throughout: the link watchdog (which runs from the
# first cycle) stays quiet.
rt=$out/realtime
start_client "$rt" --realtime
timeout 300 "$vmt" serve "$scene" --modbus "127.0.0.1:$port" --realtime --until 1.5 \
  --plc-timeout 1000 --out "$rt" >"$rt/serve.log" 2>&1
rc=$?
kill $client_pid 2>/dev/null; wait $client_pid 2>/dev/null  # it would try to reconnect
# 1: expectations after 1.5 s are not reached.
[ $rc = 0 ] || [ $rc = 1 ] || { fail "realtime serve exit $rc"; cat "$rt/serve.log" "$rt/client.log"; }
json "$rt/serve.json" 'd["mode"] == "realtime" and not d["stopped_early"]'
json "$rt/serve.json" 'all(k in d["cycle_lateness_ms"] for k in ("p50", "p99", "max"))'
json "$rt/serve.json" 'd["modbus"]["clients_accepted"] >= 1 and d["modbus"]["requests"] > 100'
json "$rt/serve.json" 'd["plc_link"] == {"timeout_ms": 1000, "timeout_cycles": 250, "lost": 0}'
grep -q '"event":"plc"' "$rt/events.jsonl" && fail "PLC lost while the client polled"

# Real time without a PLC: after 100 ms the link is lost, the NC stops with message 505.
rt=$out/realtime-no-plc
mkdir -p "$rt"
timeout 300 "$vmt" serve "$scene" --modbus 127.0.0.1:0 --realtime --no-wait-for-plc --until 0.5 \
  --out "$rt" >"$rt/serve.log" 2>&1
rc=$?
[ $rc = 1 ] || { fail "realtime serve without a PLC: exit $rc, not 1"; cat "$rt/serve.log"; }
lost='Modbus: no write from the PLC for 100 ms, the PLC link is lost'
grep -q "\"event\":\"plc\",\"state\":\"stopped\",\"reason\":\"$lost\"" "$rt/events.jsonl" ||
  fail "no PLC stopped event"
grep -q '"name":"P00S.ERRNR","value":505.0' "$rt/events.jsonl" || fail "no message 505"
json "$rt/summary.json" '"NC error: '"$lost"'" in d["failures"]'
json "$rt/serve.json" 'd["plc_link"]["lost"] == 1'

# Real time waits for the PLC's first write before its clock starts: a monitor that only reads
# is not the PLC, so with it alone the simulated time stays at 0 until serve is stopped.
rt=$out/realtime-wait
mkdir -p "$rt"
timeout 300 "$vmt" serve "$scene" --modbus 127.0.0.1:0 --realtime --until 0.5 --out "$rt" \
  >"$rt/serve.log" 2>&1 &
serve_pid=$!
mb_port=
for _ in $(seq 200); do
  mb_port=$(sed -n 's/.*Modbus TCP on 127.0.0.1:\([0-9]*\),.*/\1/p' "$rt/serve.log")
  [ -n "$mb_port" ] && break
  sleep 0.05
done
"$python" - "$mb_port" <<'PY' || fail "a reading monitor could not read"
import sys, time
from pymodbus.client import ModbusTcpClient
c = ModbusTcpClient("127.0.0.1", port=int(sys.argv[1]))
assert c.connect()
for _ in range(20):
    assert not c.read_discrete_inputs(0, 8, slave=1).isError()
    time.sleep(0.025)
# The NC status block is served while the clock waits: version 1, simulated time 0 ms.
r = c.read_input_registers(1000, 6, slave=1)
assert not r.isError() and r.registers[0] == 1 and r.registers[4:6] == [0, 0], r
c.close()
PY
grep -q "waiting for the PLC's first write" "$rt/serve.log" || fail "real time did not wait for the PLC"
kill -TERM $serve_pid; wait $serve_pid
json "$rt/serve.json" 'd["stopped_early"] and d["stop_reason"] == "signal" and d["simulated_time_s"] < 0.01'
grep -q '"event":"plc","state":"stopped"' "$rt/events.jsonl" && fail "the link was lost before the PLC came"

# Lockstep with a PLC that stops after 50 cycles: serve gives up after 1 s of wall time without
# a cycle write and still writes what it computed (as far as the cycles went: a PLC stalled for
# a second on a loaded machine ends it sooner, which changes nothing here).
start_client "$out/idle" --cycles 50
SECONDS=0
timeout 300 "$vmt" serve "$scene" --modbus "127.0.0.1:$port" --lockstep --idle-timeout 1 \
  --out "$out/idle" >"$out/idle/serve.log" 2>&1
rc=$?
kill $client_pid 2>/dev/null; wait $client_pid 2>/dev/null
[ $rc = 3 ] || { fail "idle serve: exit $rc, not 3"; cat "$out/idle/serve.log"; }
[ $SECONDS -lt 120 ] || fail "idle timeout took $SECONDS s"
json "$out/idle/serve.json" 'd["stopped_early"] and d["stop_reason"] == "idle timeout: no cycle written for 1 s"'
json "$out/idle/serve.json" '1 <= d["modbus"]["cycles"] <= 50'
json "$out/idle/serve.json" 'abs(d["simulated_time_s"] - 0.004 * d["modbus"]["cycles"]) < 1e-9'
json "$out/idle/summary.json" 'd["simulated_time_s"] < 0.21 and d["failures"]'

# The client_gone fault: embedded, the PLC's watchdog stops it (the scene expects message 505);
# served, every client is dropped and a PLC that reconnects carries on to the end.
gone=$src/scenes/fault-plc-client-gone.yaml
"$vmt" run "$gone" --out "$out/gone-embedded" >"$out/gone-embedded.log" 2>&1 ||
  { fail "embedded client_gone run"; cat "$out/gone-embedded.log"; }
grep -q '"event":"plc","state":"stopped","reason":"watchdog"' "$out/gone-embedded/events.jsonl" ||
  fail "client_gone: no watchdog event"
if start_serve "$out/gone-served" lockstep "$gone" --idle-timeout 20; then
  # It would go on trying to connect after the end: stopped once serve is done.
  timeout 300 "$python" "$src/examples/plc/repos_machine_keys.py" --port "$port" --retry 120 \
    --signals "$out/signals.json" >"$out/gone-served/client.log" 2>&1 &
  client_pid=$!
  wait $serve_pid
  kill $client_pid 2>/dev/null; wait $client_pid 2>/dev/null
  json "$out/gone-served/serve.json" 'd["stop_reason"] == "end of scene"'
  json "$out/gone-served/serve.json" 'd["modbus"]["clients_dropped"] >= 1'
  json "$out/gone-served/serve.json" 'd["modbus"]["clients_accepted"] >= 2'
  grep -q "fault: every Modbus client dropped" "$out/gone-served/serve.log" || fail "no drop logged"
fi

# Who may connect and write (tests/cli/modbus_clients.py): ten idle connections do not lock the
# PLC out and are closed after --client-timeout; monitors read but cannot write, nobody writes
# what vmt drives, another unit id gets exception 0B.
clients=$src/tests/cli/modbus_clients.py
if start_serve "$out/access" lockstep "$scene" --client-timeout 1 --idle-timeout 20; then
  timeout 60 "$python" "$clients" access "$port" "$out/signals.json" >"$out/access/client.log" 2>&1 ||
    { fail "Modbus access"; cat "$out/access/client.log"; }
  kill $serve_pid; wait $serve_pid
  json "$out/access/serve.json" 'd["modbus"]["clients_evicted"] >= 3 and d["modbus"]["clients_timed_out"] >= 7'
  json "$out/access/serve.json" 'd["modbus"]["writes_refused"] == 3 and d["modbus"]["wrong_unit"] == 2'
fi

# Listening beyond loopback needs --allow-remote (exit 2 without, a warning with); an IPv6
# loopback address in brackets works (skipped where the host has no IPv6).
"$vmt" serve "$scene" --modbus 0.0.0.0:0 --out "$out/remote" >"$out/remote.log" 2>&1
rc=$?
[ $rc = 2 ] && grep -q -- "--allow-remote" "$out/remote.log" ||
  { fail "--modbus 0.0.0.0 without --allow-remote: exit $rc"; cat "$out/remote.log"; }
"$vmt" serve "$scene" --modbus 127.0.0.1:0 --allow-client 192.0.2.1 --out "$out/remote" \
  >"$out/remote.log" 2>&1 && fail "--allow-client without --allow-remote accepted"
mkdir -p "$out/remote"
timeout 60 "$vmt" serve "$scene" --modbus 0.0.0.0:0 --allow-remote --allow-client 192.0.2.1 \
  --idle-timeout 0.5 --out "$out/remote" >"$out/remote.log" 2>&1
grep -q "warning: Modbus on 0.0.0.0:[0-9]* is reachable from the network; clients from 192.0.2.1" \
  "$out/remote.log" || { fail "no warning off loopback"; cat "$out/remote.log"; }
if "$python" -c 'import socket; s = socket.socket(socket.AF_INET6); s.bind(("::1", 0))' 2>/dev/null; then
  mkdir -p "$out/ipv6"
  timeout 300 "$vmt" serve "$scene" --modbus '[::1]:0' --out "$out/ipv6" >"$out/ipv6/serve.log" 2>&1 &
  serve_pid=$!
  v6_port=
  for _ in $(seq 1200); do
    v6_port=$(sed -n 's/.*Modbus TCP on \[::1\]:\([0-9]*\),.*/\1/p' "$out/ipv6/serve.log")
    [ -n "$v6_port" ] && break
    sleep 0.05
  done
  "$python" "$clients" read ::1 "$v6_port" || { fail "read over [::1]"; cat "$out/ipv6/serve.log"; }
  kill $serve_pid; wait $serve_pid
else
  echo "serve test: no IPv6 loopback here, [::1] skipped"
fi

# Real time under pipelined reads: seven clients keep 300 reads each in flight while the PLC
# writes. The cycle comes first: real time is held, or the late cycles are recorded and fail the
# run. A scene without expectations, so that only real time decides the exit status.
printf '%s\n' "scene: plain" "model: $src/models/lathe-c1/machine.yaml" "backend: kinematic" \
  "duration: 30" "initial: {Z: 300, X: 150, T: 0, W: 200}" "nc:" \
  "  program: $src/scenes/nc/turn_with_coolant.mtc" >"$out/plain.yaml"
# realtime_run NAME CLIENTS OPTION...: serve --realtime on the plain scene with the clients of
# modbus_clients.py (flood or plc); sets rc.
realtime_run() {
  local name=$1 what=$2
  shift 2
  mkdir -p "$out/$name"
  timeout 300 "$vmt" serve "$out/plain.yaml" --modbus 127.0.0.1:0 --realtime --no-wait-for-plc \
    --plc-timeout 1000 --out "$out/$name" "$@" >"$out/$name/serve.log" 2>&1 &
  serve_pid=$!
  local rt_port=
  for _ in $(seq 1200); do
    rt_port=$(sed -n 's/.*Modbus TCP on 127.0.0.1:\([0-9]*\),.*/\1/p' "$out/$name/serve.log")
    [ -n "$rt_port" ] && break
    sleep 0.05
  done
  timeout 120 "$python" "$clients" "$what" "$rt_port" "$out/signals.json" \
    >"$out/$name/client.log" 2>&1
  wait $serve_pid
  rc=$?
}
realtime_run flood flood --until 2
json "$out/flood/serve.json" 'd["modbus"]["requests"] > 1000 and d["plc_link"]["lost"] == 0'
if grep -q '"realtime_held": true' "$out/flood/serve.json"; then
  [ $rc = 0 ] || { fail "flood: real time held but exit $rc"; cat "$out/flood/serve.log"; }
  json "$out/flood/serve.json" 'd["cycle_lateness_ms"]["max"] <= d["cycle_lateness_ms"]["limit"]'
  grep -q '"event":"realtime"' "$out/flood/events.jsonl" && fail "flood: a late event while held"
else
  [ $rc = 1 ] || { fail "flood: real time not held but exit $rc"; cat "$out/flood/serve.log"; }
  grep -q "FAILED: real time not held" "$out/flood/serve.log" || fail "flood: no FAILED line"
  grep -q '"event":"realtime","state":"late"' "$out/flood/events.jsonl" || fail "flood: no late event"
fi
# A limit no machine keeps (1 us): the late cycles are recorded and the run fails; --allow-late
# records them and passes.
realtime_run late plc --until 0.3 --late-limit 0.001
[ $rc = 1 ] || { fail "late: exit $rc, not 1"; cat "$out/late/serve.log"; }
grep -q "FAILED: real time not held: [0-9]* cycles more than 0.001 ms late" "$out/late/serve.log" ||
  { fail "late: no FAILED line"; cat "$out/late/serve.log"; }
grep -q '"event":"realtime","state":"late","late_ms":' "$out/late/events.jsonl" ||
  fail "late: no late event"
json "$out/late/serve.json" 'not d["realtime_held"] and d["cycle_lateness_ms"]["late_cycles"] >= 1'
realtime_run allow_late plc --until 0.3 --late-limit 0.001 --allow-late
[ $rc = 0 ] || { fail "allow-late: exit $rc, not 0"; cat "$out/allow_late/serve.log"; }
json "$out/allow_late/serve.json" 'not d["realtime_held"]'

[ $fails = 0 ] && echo "serve test: all passed" || echo "serve test: $fails failed"
exit $((fails > 0))
