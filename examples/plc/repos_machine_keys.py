#!/usr/bin/python3
"""An external PLC over Modbus TCP: the repositioning manual's machine-key program (8.2), the
same logic vmt ships embedded (control/plc/programs/repos_machine_keys.cpp), here as a PLC
outside the simulation would run it against `vmt serve SCENE --lockstep`.

Each cycle, as a PLC scans: read the inputs, compute, write the outputs, then write the next
cycle number to the lockstep cycle register: vmt runs one PLC cycle of the simulation and only
then answers, so the next read sees its result. The addresses come from `vmt signals MODEL
--format json` (the PLC engineer's map). Runs until vmt ends the scene and closes the
connection.

    vmt signals models/lathe-c1/machine.yaml --format json > signals.json
    vmt serve scenes/repos-machine-keys.yaml --modbus 127.0.0.1:5020 --lockstep &
    examples/plc/repos_machine_keys.py --port 5020 --signals signals.json

With --realtime it scans on its own clock every --period ms instead and writes its outputs every
scan (against `vmt serve --realtime`, whose link watchdog stops the NC if the PLC writes nothing
for --plc-timeout; the clock starts at the PLC's first write). With
--retry S it keeps trying to connect for S seconds, at the start and after the connection
drops, as a PLC's field bus master would; a lockstep PLC then reads the cycle register to
carry on where the simulation is. --cycles N stops after N scans, a PLC that goes away.

Needs python3-pymodbus (Debian package).
"""

import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pymodbus.client import ModbusTcpClient  # noqa: E402
from pymodbus.exceptions import ModbusException  # noqa: E402
from vmt_modbus import Gateway, load_signals, plc_arguments  # noqa: E402


def connect(client, retry_s):
    """Connects, trying for up to retry_s seconds (at least once)."""
    deadline = time.monotonic() + retry_s
    while True:
        if client.connect():
            return True
        client.close()
        if time.monotonic() >= deadline:
            return False
        time.sleep(0.01)


def main():
    ap = plc_arguments(__doc__.split("\n")[0])
    ap.add_argument("--realtime", action="store_true",
                    help="scan on its own clock every --period (vmt serve --realtime)")
    ap.add_argument("--retry", type=float, default=0.0,
                    help="seconds to keep trying to connect, at the start and after a drop")
    ap.add_argument("--cycles", type=int, default=0, help="stop after this many scans (0: never)")
    args = ap.parse_args()
    signals = load_signals(args.signals)
    client = ModbusTcpClient(args.host, port=args.port)
    print(f"connecting to {args.host}:{args.port}", flush=True)
    if not connect(client, args.retry):
        print(f"cannot connect to {args.host}:{args.port}", file=sys.stderr)
        return 2
    io = Gateway(client, signals)
    repos = resta = False  # the program's outputs, held by their own contacts
    cycle = connections = 0
    next_scan = time.monotonic()
    while args.cycles == 0 or cycle < args.cycles:
        try:
            if connections > 0:
                io.forget_writes()  # a lost PLC's outputs were dropped: write them all again
                if not args.realtime:
                    cycle = io.last_cycle(cycle)  # after a drop: where the simulation is
            connections += 1
            while args.cycles == 0 or cycle < args.cycles:
                # Inputs, latched for this scan.
                io.latch(["P00S.REPOS", "mREPOS", "mRESTA", "mRaR_OFF"])
                possible = io.get("P00S.REPOS")
                key_repos, key_resta = io.get("mREPOS"), io.get("mRESTA")
                off = io.get("mRaR_OFF")
                # Network 1: repositioning / NC-block restart permitted.
                ok = possible and not off
                # Networks 2 and 3: each call holds itself until the other key or the enable
                # drops.
                repos, resta = ((key_repos or repos) and ok and not key_resta,
                                (key_resta or resta) and ok and not key_repos)
                io.set("P00C.REPOS", repos)
                io.set("P00C.RESTA", resta)
                if args.realtime:
                    # As on a field bus, every scan writes the outputs: vmt's link watchdog
                    # listens for the PLC's writes (a client that only reads is a monitor).
                    io.forget_writes()
                io.flush(["P00C.REPOS", "P00C.RESTA"])
                cycle += 1
                if args.realtime:
                    next_scan += args.period / 1000
                    time.sleep(max(0.0, next_scan - time.monotonic()))
                else:
                    io.run_cycle(cycle)
        except (ConnectionError, ModbusException, OSError):
            # vmt has ended the scene, or dropped the connection: try again if asked to.
            client.close()
            if args.retry <= 0 or not connect(client, args.retry):
                break
            next_scan = time.monotonic()
    client.close()
    print(f"repos_machine_keys: {cycle} cycles, {connections} connections")
    return 0 if cycle > 0 else 1


if __name__ == "__main__":
    sys.exit(main())
