#!/usr/bin/python3
"""An external PLC over Modbus TCP: the C-axis manual's typical SPS program (4.4), the spindle
<-> rotary axis (C) changeover of a lathe whose C servo drives the spindle through clutch K. The
same logic vmt ships embedded (control/plc/programs/c_axis_changeover.cpp, whose comments give
the networks and what vmt adds), run against `vmt serve SCENE --lockstep`:

    vmt signals models/lathe-c1/machine.yaml --format json > signals.json
    vmt serve scenes/c-axis-spiral-groove.yaml --modbus 127.0.0.1:5020 --lockstep &
    examples/plc/c_axis_changeover.py --port 5020 --signals signals.json

With --wrong it runs the deliberately wrong variant (acknowledges ROTMOD_Q as soon as the valve
is switched, without waiting for IROTMODE), whose consequence the NC reports: against
scenes/fault-changeover-wrong-plc.yaml, C lags on the spindle's encoder and the NC stops with
504, as with the embedded c_axis_changeover_wrong (tests/cli/serve_test.sh).
machine_panel.py runs this program as one of its networks.

Needs python3-pymodbus (Debian package).
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vmt_modbus import load_signals, plc_arguments, run_lockstep  # noqa: E402

HUNTING_SPINDLE = 0b00000001  # 65012 bit 0
SPEED_SPEC = 0b00000100       # 65012 bit 2
NO_FUNCTION = 0b00000000


class TON:
    """On-delay, as IEC 61131-3 (and vmt's TON): times in ms."""

    def __init__(self):
        self.q, self.start, self.before = False, 0, False

    def __call__(self, IN, PT, now):
        if not IN:
            self.q = False
        else:
            if not self.before:
                self.start = now
            if not self.q:
                self.q = now - self.start >= PT
        self.before = IN
        return self.q


class CAxisChangeover:
    """The program of 4.4 with vmt's additions; `signals` is the map of `vmt signals`."""

    def __init__(self, signals, process=0, wrong=False):
        table = signals["signals"]
        sp = [s for s in table if s["pattern"] == "Axx.ROTMOD"]
        if len(sp) != 1:
            raise ValueError("needs exactly one main spindle with ROTMOD/SPMOD")
        self.ISP_NR = sp[0]["instance"]
        rot = [s for s in table if s["pattern"] == "Axx.AXD.65012"
               and s["instance"] != self.ISP_NR]
        if len(rot) > 1:
            rot = [s for s in rot if s.get("axis_name") == "C"]
        if len(rot) != 1:
            raise ValueError("needs one rotary axis (C) besides the spindle")
        self.IROT_NR = rot[0]["instance"]
        a = lambda pattern, n: pattern.replace("xx", f"{n:02d}", 1)  # noqa: E731
        sp, ro = self.ISP_NR, self.IROT_NR
        self.ROTMOD, self.ROTMOD_Q = a("Axx.ROTMOD", sp), a("Axx.ROTMOD_Q", sp)
        self.SPMOD, self.SPMOD_Q = a("Axx.SPMOD", sp), a("Axx.SPMOD_Q", sp)
        self.SP = [a(f"Axx.AXD.{i}", sp) for i in (65012, 65013, 65014, 65015)]
        self.ROT = [a(f"Axx.AXD.{i}", ro) for i in (65012, 65013, 65014, 65015)]
        self.SP_C_READY, self.ROT_C_READY = a("AxxC.READY", sp), a("AxxC.READY", ro)
        self.STOP, self.MSG_WR = f"P{process:02d}S.STOP", f"P{process:02d}.MSG_WR"
        self.inputs = [self.ROTMOD, self.SPMOD, "IROTMODE", "ISPMODE", self.STOP]
        self.outputs = ([self.ROTMOD_Q, self.SPMOD_Q, self.SP_C_READY, self.ROT_C_READY,
                         "QROTMODE", "QSPMODE", self.MSG_WR] + self.SP + self.ROT)
        self.wrong = wrong
        # The manual's 100 1/min, 500 rad/s^2, 0 deg for the spindle; vmt's hunting values
        # for the C servo; T_CLUTCH 5 s; messages 220 / 221.
        self.init = {self.SP[1]: 1000000, self.SP[2]: 500, self.SP[3]: 0,
                     self.ROT[1]: 10000, self.ROT[2]: 10, self.ROT[3]: 0}
        self.T_CLUTCH, self.MSG_ROTERR, self.MSG_SPERR = 5000, 220, 221
        self.READY = False
        self.MPEND1R = self.MPENDOR = self.MPEND1S = self.MPENDOS = False
        self.M_ROTERR = self.M_SPERR = False
        self.T_ROT, self.T_SP = TON(), TON()
        self.msg_written = 0

    def scan(self, io, now_ms):
        g, out = io.get, io.set
        if not self.READY:  # networks 1-6: the AXD idents, in the first scan
            for name, value in self.init.items():
                out(name, value)
            self.READY = True
        IROT, ISP, STOP = g("IROTMODE"), g("ISPMODE"), g(self.STOP)
        engaged, released = IROT and not ISP, ISP and not IROT

        M_ROTAC = g(self.ROTMOD) and not g(self.SPMOD)
        if M_ROTAC:
            if self.MPEND1S and not self.MPENDOS:
                out(self.SP[0], NO_FUNCTION)
            self.MPENDOS = self.MPEND1S = False
            out(self.ROT_C_READY, True)
            if not IROT and not self.MPEND1R and not STOP and not self.M_ROTERR:
                out(self.ROT[0], SPEED_SPEC)  # hunting ON
                self.MPEND1R = True
            out("QSPMODE", False)
            out("QROTMODE", True)
            if engaged and not self.MPENDOR:
                out(self.ROT[0], NO_FUNCTION)  # hunting OFF
                self.MPENDOR = True
                out(self.SP_C_READY, False)
        if self.T_ROT(M_ROTAC and not engaged and not STOP, self.T_CLUTCH, now_ms):
            self.M_ROTERR = True
        if not M_ROTAC or engaged:
            self.M_ROTERR = False
        if (STOP or self.M_ROTERR) and self.MPEND1R and not self.MPENDOR:
            out(self.ROT[0], NO_FUNCTION)
            self.MPEND1R = False
        if self.wrong:
            # The wrong variant: acknowledged with the valve, before the clutch has meshed.
            out(self.ROTMOD_Q, M_ROTAC)
        else:
            out(self.ROTMOD_Q, engaged and self.MPENDOR)

        M_SPLAC = g(self.SPMOD)
        if M_SPLAC:
            if self.MPEND1R and not self.MPENDOR:
                out(self.ROT[0], NO_FUNCTION)
            self.MPENDOR = self.MPEND1R = False
            out(self.SP_C_READY, True)
            out(self.ROT_C_READY, False)
            if not ISP and not self.MPEND1S and not STOP and not self.M_SPERR:
                out(self.SP[0], HUNTING_SPINDLE)
                self.MPEND1S = True
            out("QROTMODE", False)
            out("QSPMODE", True)
            if released and not self.MPENDOS:
                out(self.SP[0], NO_FUNCTION)
                self.MPENDOS = True
        if self.T_SP(M_SPLAC and not released and not STOP, self.T_CLUTCH, now_ms):
            self.M_SPERR = True
        if not M_SPLAC or released:
            self.M_SPERR = False
        if (STOP or self.M_SPERR) and self.MPEND1S and not self.MPENDOS:
            out(self.SP[0], NO_FUNCTION)
            self.MPEND1S = False
        out(self.SPMOD_Q, released)

        msg = self.MSG_ROTERR if self.M_ROTERR else self.MSG_SPERR if self.M_SPERR else 0
        if msg != self.msg_written:
            if msg != 0 or io.values.get(self.MSG_WR, 0) == self.msg_written:
                out(self.MSG_WR, msg)
            self.msg_written = msg


def main():
    ap = plc_arguments(__doc__.split("\n")[0])
    ap.add_argument("--wrong", action="store_true", help="the wrong variant (see above)")
    args = ap.parse_args()
    signals = load_signals(args.signals)
    program = CAxisChangeover(signals, wrong=args.wrong)
    return run_lockstep(args, signals, "c_axis_changeover", program.inputs, program.outputs,
                        program.scan)


if __name__ == "__main__":
    sys.exit(main())
