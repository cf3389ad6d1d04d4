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

Needs python3-pymodbus (Debian package).
"""

import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pymodbus.client import ModbusTcpClient  # noqa: E402
from pymodbus.exceptions import ModbusException  # noqa: E402
from vmt_modbus import Gateway  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--host", default="127.0.0.1")
    ap.add_argument("--port", type=int, required=True)
    ap.add_argument("--signals", required=True, help="vmt signals MODEL --format json")
    args = ap.parse_args()
    with open(args.signals, encoding="utf-8") as f:
        signals = json.load(f)
    client = ModbusTcpClient(args.host, port=args.port)
    if not client.connect():
        print(f"cannot connect to {args.host}:{args.port}", file=sys.stderr)
        return 2
    io = Gateway(client, signals)
    repos = resta = False  # the program's outputs, held by their own contacts
    cycle = 0
    try:
        while True:
            # Inputs, latched for this scan.
            io.latch(["P00S.REPOS", "mREPOS", "mRESTA", "mRaR_OFF"])
            possible = io.get("P00S.REPOS")
            key_repos, key_resta = io.get("mREPOS"), io.get("mRESTA")
            off = io.get("mRaR_OFF")
            # Network 1: repositioning / NC-block restart permitted.
            ok = possible and not off
            # Networks 2 and 3: each call holds itself until the other key or the enable drops.
            repos, resta = ((key_repos or repos) and ok and not key_resta,
                            (key_resta or resta) and ok and not key_repos)
            io.set("P00C.REPOS", repos)
            io.set("P00C.RESTA", resta)
            io.flush(["P00C.REPOS", "P00C.RESTA"])
            cycle += 1
            io.run_cycle(cycle)
    except (ConnectionError, ModbusException, OSError):
        pass  # vmt has ended the scene and closed the connection
    finally:
        client.close()
    print(f"repos_machine_keys: {cycle} cycles")
    return 0 if cycle > 0 else 1


if __name__ == "__main__":
    sys.exit(main())
