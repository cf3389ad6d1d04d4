"""The process image of `vmt serve` as an external PLC sees it over Modbus TCP: signals by name
through the map `vmt signals MODEL --format json` gives, read once per scan (a few requests per
area, as a PLC's field bus would) and written where they changed.

Needs python3-pymodbus (Debian package).
"""

import argparse
import json
import sys

from pymodbus.client import ModbusTcpClient
from pymodbus.exceptions import ModbusException

_READ = {  # area -> (pymodbus reader name, items per request, bit area?)
    "coil": ("read_coils", 2000, True),
    "discrete_input": ("read_discrete_inputs", 2000, True),
    "holding_register": ("read_holding_registers", 125, False),
    "input_register": ("read_input_registers", 125, False),
}


class Gateway:
    """`latch(names)` reads the inputs of a scan; `get` and `set` work on the latched values;
    `flush()` writes the outputs that changed; `run_cycle(n)` steps vmt in lockstep."""

    def __init__(self, client: ModbusTcpClient, signals: dict):
        self.client = client
        # The NC status block's registers (read only) are latched by name like the signals.
        listed = signals["signals"] + signals.get("nc_status", [])
        self.where = {s["name"]: s["modbus"] for s in listed}
        self.types = {s["name"]: s["type"] for s in listed}
        self.cycle_register = signals["modbus"]["lockstep_cycle_register"]
        self.axd_wr_register = signals["modbus"].get("axd_wr_register")
        self.values = {}
        self.written = {}

    def _check(self, reply, what):
        if reply.isError():
            raise ConnectionError(f"{what}: {reply}")
        return reply

    def latch(self, names):
        """Reads the named BOOL and INT signals, one request per area and span."""
        spans = {}
        for name in names:
            a = self.where[name]
            lo, hi = spans.get(a["area"], (a["address"], a["address"]))
            spans[a["area"]] = (min(lo, a["address"]), max(hi, a["address"] + a["count"] - 1))
        data = {}
        for area, (lo, hi) in spans.items():
            reader, most, bits = _READ[area]
            got = []
            for start in range(lo, hi + 1, most):
                n = min(most, hi + 1 - start)
                r = self._check(getattr(self.client, reader)(start, n, slave=1), f"reading {area}")
                got += list(r.bits[:n]) if bits else list(r.registers[:n])
            data[area] = (lo, got)
        for name in names:
            a = self.where[name]
            lo, got = data[a["area"]]
            v = got[a["address"] - lo]
            t = self.types[name]
            if a["area"] in ("coil", "discrete_input"):
                self.values[name] = bool(v)
            elif t == "INT":
                self.values[name] = v - 65536 if v >= 32768 else v
            elif t in ("WORD", "UINT"):
                self.values[name] = v
            elif t in ("DINT", "UDINT", "DWORD"):
                v = v << 16 | got[a["address"] - lo + 1]  # most significant word first
                self.values[name] = v - (1 << 32) if t == "DINT" and v >= 1 << 31 else v
            else:
                raise ValueError(f"{name}: only BOOL, INT, UINT, WORD and DINT signals here")

    def get(self, name):
        return self.values[name]

    def set(self, name, value):
        self.values[name] = value

    def flush(self, names):
        """Writes the named outputs (coils, and INT / WORD / DINT holding registers) whose
        value differs from what was last written."""
        for name in names:
            a = self.where[name]
            if a["area"] == "coil":
                v = bool(self.values.get(name, False))
            elif a["area"] == "holding_register" and self.types[name] in ("INT", "WORD", "DINT"):
                v = int(self.values.get(name, 0))
            else:
                raise ValueError(f"{name} is not a BOOL, INT, WORD or DINT the PLC writes")
            if self.written.get(name) == v:
                continue
            if a["area"] == "coil":
                r = self.client.write_coil(a["address"], v, slave=1)
            elif a["count"] == 1:
                r = self.client.write_register(a["address"], v % 65536, slave=1)
            else:
                u = v % (1 << 32)
                r = self.client.write_registers(a["address"], [u >> 16, u & 0xFFFF], slave=1)
            self._check(r, f"writing {name}")
            self.written[name] = v

    def forget_writes(self):
        """The next flush writes every output again (after a reconnection)."""
        self.written = {}

    def last_cycle(self, cycle):
        """The simulation's last cycle after a drop: `cycle` if its write ran, else the one
        before (the register holds the number modulo 65536)."""
        r = self._check(self.client.read_holding_registers(self.cycle_register, 1, slave=1),
                        "reading the cycle register")
        return cycle - 1 + (r.registers[0] - (cycle - 1)) % 65536

    AXD_WR_RESULTS = {1: "done", 2: "no axis", 3: "refused"}

    def axd_wr(self, axis, ident, value):
        """AXD_WR (fast-measurement 7.2): S-0-`ident` := `value` in the drive of axis number
        `axis`, through vmt serve's AXD_WR block; one FC23 writes the request and reads the
        result back. Returns "done", "no axis" or "refused"."""
        u = int(value) % (1 << 32)
        r = self._check(
            self.client.readwrite_registers(
                read_address=self.axd_wr_register + 4, read_count=1,
                write_address=self.axd_wr_register,
                write_registers=[axis, ident, u >> 16, u & 0xFFFF],
                slave=1),
            f"AXD_WR axis {axis} S-0-{ident}")
        return self.AXD_WR_RESULTS[r.registers[0]]

    def run_cycle(self, number):
        self._check(self.client.write_register(self.cycle_register, number % 65536, slave=1),
                    f"cycle {number}")


def plc_arguments(description):
    """The command line every example PLC shares: where vmt serves and the signal map."""
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("--host", default="127.0.0.1")
    ap.add_argument("--port", type=int, required=True)
    ap.add_argument("--signals", required=True, help="vmt signals MODEL --format json")
    ap.add_argument("--period", type=float, default=4.0, help="the scene's PLC period, ms")
    return ap


def run_lockstep(args, signals, name, inputs, outputs, scan):
    """Scans as a PLC does against `vmt serve --lockstep` until vmt ends the scene: latch
    `inputs`, `scan(io, now_ms)`, write the changed `outputs`, then the next cycle number, which
    vmt answers only after it ran that PLC cycle. Returns the exit status."""
    client = ModbusTcpClient(args.host, port=args.port)
    if not client.connect():
        print(f"cannot connect to {args.host}:{args.port}", file=sys.stderr)
        return 2
    io, cycle = Gateway(client, signals), 0
    try:
        while True:
            io.latch(inputs)
            scan(io, cycle * args.period)
            io.flush(outputs)
            cycle += 1
            io.run_cycle(cycle)
    except (ConnectionError, ModbusException, OSError):
        pass  # vmt has ended the scene and closed the connection
    finally:
        client.close()
    print(f"{name}: {cycle} cycles")
    return 0 if cycle > 0 else 1


def load_signals(path):
    """The map of `vmt signals MODEL --format json`."""
    with open(path, encoding="utf-8") as f:
        return json.load(f)
