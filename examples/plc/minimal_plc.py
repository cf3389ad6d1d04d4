#!/usr/bin/python3
"""A minimal external PLC for vmt, in plain Python (standard library only): it selects automatic
mode, gives one cycle start, acknowledges the NC's auxiliary functions with the four-phase
AUXSTB/AUXACK handshake (M08/M09 switch the coolant pump, M08 is acknowledged once the pressure
switch reports flow), and watches the NC status block (positions, program state, messages)
until vmt ends the scene. docs/plc.md explains every step.

    vmt signals models/lathe-c1/machine.yaml --format json > signals.json
    vmt serve examples/plc/minimal_plc.yaml --modbus 127.0.0.1:5020 &
    examples/plc/minimal_plc.py --port 5020 --signals signals.json

Exit status 0 when the NC reported the program's end (NC.STATE 3), 1 otherwise.
"""

import argparse
import json
import socket
import struct
import sys
import time


class ModbusTcp:
    """The five Modbus TCP requests a PLC needs, over one connection (unit id 1)."""

    def __init__(self, host, port, timeout=30.0):
        self.sock = socket.create_connection((host, port), timeout)
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.tid = 0

    def _recv(self, n):
        data = b""
        while len(data) < n:
            chunk = self.sock.recv(n - len(data))
            if not chunk:
                raise ConnectionError("vmt closed the connection")
            data += chunk
        return data

    def _call(self, pdu):
        self.tid = (self.tid + 1) % 65536
        self.sock.sendall(struct.pack(">HHHB", self.tid, 0, len(pdu) + 1, 1) + pdu)
        _, _, length, _ = struct.unpack(">HHHB", self._recv(7))
        reply = self._recv(length - 1)
        if reply[0] & 0x80:
            raise RuntimeError(f"function {pdu[0]}: Modbus exception {reply[1]}")
        return reply

    def read_bits(self, function, address, count):  # 1 coils, 2 discrete inputs
        r = self._call(struct.pack(">BHH", function, address, count))
        return [bool(r[2 + i // 8] >> (i % 8) & 1) for i in range(count)]

    def read_registers(self, function, address, count):  # 3 holding, 4 input registers
        r = self._call(struct.pack(">BHH", function, address, count))
        return list(struct.unpack(f">{count}H", r[2:2 + 2 * count]))

    def write_coil(self, address, value):
        self._call(struct.pack(">BHH", 5, address, 0xFF00 if value else 0))

    def write_register(self, address, value):
        self._call(struct.pack(">BHH", 6, address, value % 65536))

    def close(self):
        self.sock.close()


def dint(words, at):
    v = words[at] << 16 | words[at + 1]  # most significant word first
    return v - (1 << 32) if v >= 1 << 31 else v


STATES = {0: "idle", 1: "running", 2: "held", 3: "ended", 4: "error"}


class MinimalPlc:
    def __init__(self, signals):
        where = {s["name"]: s["modbus"] for s in signals["signals"]}
        # The main spindle's axis number (A03 on lathe-c1): the one with ROTMOD/SPMOD.
        sp = [s["name"][:3] for s in signals["signals"] if s["pattern"] == "Axx.ROTMOD"][0]
        self.ROTMOD, self.SPMOD = sp + ".ROTMOD", sp + ".SPMOD"
        # The C servo that drives the spindle through clutch K in rotary axis mode (A04).
        rot = [s["name"][:3] for s in signals["signals"]
               if s["pattern"] == "Axx.AXD.65012" and not s["name"].startswith(sp)][0]
        self.SP_READY, self.ROT_READY = sp[:3] + "C.READY", rot + "C.READY"
        self.INPUTS = ["P00S.AUTO", "P00S.AUXSTB", "ICOOLANT_PRESSURE",
                       self.ROTMOD, self.SPMOD, "IROTMODE", "ISPMODE"]
        self.OUTPUTS = ["P00C.AUTO", "P00C.START", "P00C.AUXACK", "QCOOLANT",
                        self.ROTMOD + "_Q", self.SPMOD + "_Q", "QROTMODE", "QSPMODE",
                        self.SP_READY, self.ROT_READY]
        self.bit = {n: where[n]["address"] for n in self.INPUTS + self.OUTPUTS}
        self.mfunc = where["P00S.MFUNC"]["address"]  # INT input register, -1: none
        self.inputs = 1 + max(self.bit[n] for n in self.INPUTS)
        m = signals["modbus"]
        self.cycle_register = m["lockstep_cycle_register"]
        self.status = m["nc_status_register"]
        status = {s["name"]: s for s in signals["nc_status"]}
        self.axes = [(s["name"][:3], s["meaning"].split(":")[0].split()[-1], s["unit"])
                     for s in signals["nc_status"] if s["name"].endswith(".NC_POS")]
        self.status_count = 32 + 8 * len(self.axes)
        assert status["NC.STATE"]["modbus"]["address"] == self.status + 7
        self.out = {n: False for n in self.OUTPUTS}
        self.started = self.ack = self.coolant = False
        self.state = self.messages = None
        self.ended = False
        self.first = self.last = None

    def scan(self, mb):
        di = mb.read_bits(2, 0, self.inputs)
        x = {n: di[self.bit[n]] for n in self.INPUTS}
        mfunc = mb.read_registers(4, self.mfunc, 1)[0]
        mfunc = mfunc - 65536 if mfunc >= 32768 else mfunc
        # 1. Automatic mode: a rising edge of P00C.AUTO asks for it; P00S.AUTO confirms it.
        self.out["P00C.AUTO"] = not x["P00S.AUTO"] and not self.out["P00C.AUTO"]
        # 2. One cycle start (a rising edge) once the NC is in automatic mode.
        self.out["P00C.START"] = x["P00S.AUTO"] and not self.started
        self.started = self.started or self.out["P00C.START"]
        # 3. Auxiliary functions, four phases: AUXSTB rises -> do the function -> AUXACK high
        #    -> the NC drops AUXSTB -> AUXACK low -> (a scan later) the next AUXSTB.
        if x["P00S.AUXSTB"] and not self.ack:
            if mfunc == 8:
                self.coolant = True
            if mfunc == 9:
                self.coolant = False
            self.ack = mfunc != 8 or x["ICOOLANT_PRESSURE"]  # M08: wait for the flow
        elif not x["P00S.AUXSTB"]:
            self.ack = False
        self.out["P00C.AUXACK"] = self.ack
        self.out["QCOOLANT"] = self.coolant
        # 4. The headstock (C-axis manual 4.4): the NC asks for spindle mode (SPMOD, also at
        #    power-on) or rotary axis mode (ROTMOD); the valves move clutch K and the PLC
        #    acknowledges the mode once the clutch's switches confirm it. (A C-axis program also
        #    needs the hunting motion, AXD idents 65012..65014: c_axis_changeover.py.)
        engaged = x["IROTMODE"] and not x["ISPMODE"]
        released = x["ISPMODE"] and not x["IROTMODE"]
        if x[self.ROTMOD] != x[self.SPMOD]:  # a request; between requests the valves hold
            self.out["QROTMODE"], self.out["QSPMODE"] = x[self.ROTMOD], x[self.SPMOD]
        self.out[self.ROTMOD + "_Q"] = x[self.ROTMOD] and engaged
        self.out[self.SPMOD + "_Q"] = released
        # AxxC.READY switches the drives' controller enable: the spindle's drive turns only
        # with it (in spindle mode), the C servo only in rotary axis mode.
        self.out[self.SP_READY] = not (x[self.ROTMOD] and engaged)
        self.out[self.ROT_READY] = x[self.ROTMOD]
        # The outputs every scan, as a field bus carries them: in real time vmt's link watchdog
        # takes a PLC that writes nothing for --plc-timeout (100 ms) for a dead one.
        for name, value in self.out.items():
            mb.write_coil(self.bit[name], value)
        self.watch(mb.read_registers(4, self.status, self.status_count))

    def watch(self, w):
        """The NC status block: program state, messages, axis positions."""
        now_s = dint(w, 4) / 1000  # NC.TIME_MS: the simulated time
        state, count = w[7], w[10]
        messages = [(w[12 + 2 * k], "NC" if w[13 + 2 * k] == 1 else "PLC")
                    for k in range(min(count, 8))]
        positions = [dint(w, 32 + 8 * i) * 1e-4 for i in range(len(self.axes))]
        if self.first is None:
            self.first = positions
        self.last = positions
        if state != self.state:
            where = ", ".join(f"{name} {p:.4f}" for (_, name, _), p in zip(self.axes, positions))
            print(f"{now_s:7.3f} s: NC {STATES.get(state, state)}, line {dint(w, 8)}; {where}")
            self.state = state
        if messages != self.messages:
            print(f"{now_s:7.3f} s: messages {messages}")
            self.messages = messages
        self.ended = self.ended or state == 3


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--host", default="127.0.0.1")
    ap.add_argument("--port", type=int, required=True)
    ap.add_argument("--signals", required=True, help="vmt signals MODEL --format json")
    ap.add_argument("--period", type=float, default=4.0, help="PLC scan, ms")
    ap.add_argument("--realtime", action="store_true",
                    help="vmt serve --realtime: scan on the wall clock instead of lockstep")
    args = ap.parse_args()
    with open(args.signals, encoding="utf-8") as f:
        plc = MinimalPlc(json.load(f))
    mb = ModbusTcp(args.host, args.port)
    cycle = 0
    try:
        while True:
            plc.scan(mb)
            cycle += 1
            if args.realtime:
                time.sleep(args.period / 1000)
            else:
                mb.write_register(plc.cycle_register, cycle)  # vmt answers after the cycle ran
    except (ConnectionError, OSError):
        pass  # vmt has ended the scene and closed the connection
    finally:
        mb.close()
    for (axis, name, unit), a, b in zip(plc.axes, plc.first or [], plc.last or []):
        print(f"axis {name} ({axis}): {a:.4f} -> {b:.4f} [{unit.split()[1]}]")
    print(f"minimal_plc: {cycle} scans, program {'ended' if plc.ended else 'did not end'}")
    return 0 if plc.ended else 1


if __name__ == "__main__":
    sys.exit(main())
