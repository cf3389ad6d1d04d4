"""The process image of `vmt serve` as an external PLC sees it over Modbus TCP: signals by name
through the map `vmt signals MODEL --format json` gives, read once per scan (a few requests per
area, as a PLC's field bus would) and written where they changed.

Needs python3-pymodbus (Debian package).
"""

from pymodbus.client import ModbusTcpClient

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
        self.where = {s["name"]: s["modbus"] for s in signals["signals"]}
        self.types = {s["name"]: s["type"] for s in signals["signals"]}
        self.cycle_register = signals["modbus"]["lockstep_cycle_register"]
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
            elif t == "WORD":
                self.values[name] = v
            elif t in ("DINT", "UDINT", "DWORD"):
                v = v << 16 | got[a["address"] - lo + 1]  # most significant word first
                self.values[name] = v - (1 << 32) if t == "DINT" and v >= 1 << 31 else v
            else:
                raise ValueError(f"{name}: only BOOL, INT, WORD and DINT signals here")

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

    def run_cycle(self, number):
        self._check(self.client.write_register(self.cycle_register, number % 65536, slave=1),
                    f"cycle {number}")
