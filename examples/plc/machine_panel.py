#!/usr/bin/python3
"""An external PLC over Modbus TCP: lathe-c1's panel and machine program, the same logic vmt
ships embedded (control/plc/programs/machine_panel.cpp), run against `vmt serve SCENE
--lockstep`: panel keys to the NC's control signals, the door, tailstock quill and coolant with
their interlocks, M08 acknowledged on the coolant pressure, the repositioning keys (8.2) and the
C-axis changeover (C-axis manual 4.4, c_axis_changeover.py).

    vmt signals models/lathe-c1/machine.yaml --format json > signals.json
    vmt serve scenes/machine-panel.yaml --modbus 127.0.0.1:5020 --lockstep &
    examples/plc/machine_panel.py --port 5020 --signals signals.json

Needs python3-pymodbus (Debian package).
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from c_axis_changeover import CAxisChangeover  # noqa: E402
from vmt_modbus import load_signals, plc_arguments, run_lockstep  # noqa: E402

KEYS = ["mAUTO", "mMANU", "mSTART", "mSTOP", "mRESET", "mSBL", "mCOOLANT", "mDOOR",
        "mTAILSTOCK", "mREPOS", "mRESTA", "mRaR_OFF"]
JOG = {"mJGPOS_X": "A01C.JGPOS", "mJGNEG_X": "A01C.JGNEG",
       "mJGPOS_Z": "A02C.JGPOS", "mJGNEG_Z": "A02C.JGNEG"}
# The jog mode selector: each key toggles its bit of the code on P00C.JOGM0..2.
JOG_MODE = {"mJOGM0": "P00C.JOGM0", "mJOGM1": "P00C.JOGM1", "mJOGM2": "P00C.JOGM2"}
# The override switches (selectors, INT positions in percent) are the NC's overrides.
OVERRIDES = {"mFOVR": "P00C.FOVR", "mSOVR_S1": "A03C.SOVR"}
INPUTS = KEYS + list(JOG) + list(JOG_MODE) + list(OVERRIDES) + ["P00S.RUN", "P00S.AUXSTB", "P00S.MFUNC", "P00S.REPOS",
                             "A03S.N_NMIN", "IDOOR_CLOSED", "ICOOLANT_PRESSURE"]
# P00C.REPOS/RESTA hold themselves (8.2): the program reads back what it wrote.
OUTPUTS = ["P00C.AUTO", "P00C.MANU", "P00C.RESET", "P00C.SBL", "P00C.STOP", "P00C.START",
           "P00C.AUXACK", "P00C.REPOS", "P00C.RESTA", "QDOOR_OPEN", "QTAILSTOCK",
           "QCOOLANT"] + list(JOG.values()) + list(JOG_MODE.values()) + list(OVERRIDES.values())


class Edge:
    """R_TRIG."""

    def __init__(self):
        self.last = False

    def __call__(self, clk):
        q = clk and not self.last
        self.last = clk
        return q


class MachinePanel:
    def __init__(self, hold_ack=False):
        # The auxiliary functions' handshake: pulse AUXACK for one scan (the embedded program's
        # way), or hold it until the strobe falls (four phases, as many PLC programmers write
        # it). vmt raises the next strobe only after AUXACK is low and the strobe has been low
        # for a scan, so both work alike.
        self.hold_ack = hold_ack
        self.edges = {k: Edge() for k in ("mSTART", "mSTOP", "mSBL", "mCOOLANT", "mDOOR",
                                          "mTAILSTOCK", *JOG_MODE)}
        self.jog_mode = {k: False for k in JOG_MODE}
        self.feed_hold = self.single_block = self.coolant = self.door_open = False
        self.quill = self.aux_acked = False

    def scan(self, io):
        g = io.get
        running, at_rest, door_closed = g("P00S.RUN"), g("A03S.N_NMIN"), g("IDOOR_CLOSED")
        edge = {k: e(g(k)) for k, e in self.edges.items()}
        if edge["mDOOR"]:
            self.door_open = False if self.door_open else (not running and at_rest)
        io.set("QDOOR_OPEN", self.door_open)
        io.set("P00C.AUTO", g("mAUTO"))
        io.set("P00C.MANU", g("mMANU"))
        io.set("P00C.RESET", g("mRESET"))
        if edge["mSBL"]:
            self.single_block = not self.single_block
        io.set("P00C.SBL", self.single_block)
        if edge["mSTOP"]:
            self.feed_hold = True
        if edge["mSTART"] and door_closed:
            self.feed_hold = False
        io.set("P00C.STOP", self.feed_hold or not door_closed)
        io.set("P00C.START", g("mSTART") and not self.feed_hold and door_closed)
        for key, signal in JOG.items():
            io.set(signal, g(key) and door_closed)
        for key, signal in JOG_MODE.items():
            if edge[key]:
                self.jog_mode[key] = not self.jog_mode[key]
            io.set(signal, self.jog_mode[key])
        for key, signal in OVERRIDES.items():
            io.set(signal, g(key))
        if edge["mTAILSTOCK"] and not running:
            self.quill = not self.quill
        io.set("QTAILSTOCK", self.quill)
        if edge["mCOOLANT"]:
            self.coolant = not self.coolant
        strobe = g("P00S.AUXSTB")
        m = g("P00S.MFUNC") if strobe else -1
        if m == 8:
            self.coolant = True
        if m == 9:
            self.coolant = False
        io.set("QCOOLANT", self.coolant)
        done = strobe and (m != 8 or g("ICOOLANT_PRESSURE"))
        if self.hold_ack:
            ack = done or (self.aux_acked and strobe)
        else:
            ack = done and not self.aux_acked
        io.set("P00C.AUXACK", ack)
        self.aux_acked = ack
        # Repositioning manual 8.2, networks 1 to 3.
        ok = g("P00S.REPOS") and not g("mRaR_OFF")
        repos = (g("mREPOS") or io.values.get("P00C.REPOS", False)) and ok and not g("mRESTA")
        resta = (g("mRESTA") or io.values.get("P00C.RESTA", False)) and ok and not g("mREPOS")
        io.set("P00C.REPOS", repos)
        io.set("P00C.RESTA", resta)


def main():
    ap = plc_arguments(__doc__.split("\n")[0])
    ap.add_argument("--hold-ack", action="store_true",
                    help="hold AUXACK until AUXSTB falls (four-phase handshake) instead of a pulse")
    args = ap.parse_args()
    signals = load_signals(args.signals)
    program, changeover = MachinePanel(args.hold_ack), CAxisChangeover(signals)

    def scan(io, now_ms):
        program.scan(io)
        changeover.scan(io, now_ms)

    return run_lockstep(args, signals, "machine_panel", INPUTS + changeover.inputs,
                        OUTPUTS + changeover.outputs, scan)


if __name__ == "__main__":
    sys.exit(main())
