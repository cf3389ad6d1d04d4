#!/usr/bin/env python3
"""Modbus TCP clients that misbehave, for tests/cli/serve_test.sh (standard library only).

  access PORT SIGNALS   lockstep serve with --client-timeout 1: ten idle connections, then the
                        PLC connects and runs cycles; monitors may read but not write, nobody
                        writes what vmt drives, other unit ids get exception 0B; the idle ones
                        are closed after the timeout while the PLC goes on.
  flood PORT SIGNALS    real-time serve: a PLC writes every 10 ms while seven clients keep 300
                        reads each in flight, until serve ends.
  plc PORT SIGNALS      real-time serve: only the PLC, writing every 10 ms until serve ends.
  read HOST PORT        one read of input register 1000 (the NC status block's version).
Exit 0 when every check held; a failed check prints what it got.
"""

import json
import socket
import struct
import sys
import threading
import time


class Conn:
    def __init__(self, port, host="127.0.0.1"):
        self.sock = socket.create_connection((host, port), timeout=5)
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.tid = 0

    def call(self, pdu, unit=1):
        """Sends one request, returns the reply's PDU (function code first)."""
        self.tid = (self.tid + 1) % 65536
        self.sock.sendall(struct.pack(">HHHB", self.tid, 0, len(pdu) + 1, unit) + pdu)
        head = self.recv(7)
        tid, _, length, got_unit = struct.unpack(">HHHB", head)
        assert tid == self.tid and got_unit == unit, (tid, self.tid, got_unit, unit)
        return self.recv(length - 1)

    def recv(self, n):
        out = b""
        while len(out) < n:
            chunk = self.sock.recv(n - len(out))
            if not chunk:
                raise ConnectionError("closed by the server")
            out += chunk
        return out

    def closed(self, wait_s):
        """True if the server closes the connection within wait_s."""
        self.sock.settimeout(wait_s)
        try:
            return self.sock.recv(1) == b""
        except (socket.timeout, TimeoutError):
            return False
        except ConnectionResetError:
            return True


def write_register(c, address, value, unit=1):
    return c.call(struct.pack(">BHH", 6, address, value % 65536), unit)


def write_coil(c, address, on, unit=1):
    return c.call(struct.pack(">BHH", 5, address, 0xFF00 if on else 0), unit)


def read_input_registers(c, address, count, unit=1):
    return c.call(struct.pack(">BHH", 4, address, count), unit)


failures = []


def check(what, ok, got=None):
    if not ok:
        failures.append(what)
        print(f"FAIL {what}: got {got!r}")


def access(port, signals):
    where = {s["name"]: s["modbus"] for s in signals["signals"]}
    fovr = where["P00C.FOVR"]["address"]
    ev29 = where["P00.EV29"]["address"]
    cycle = signals["modbus"]["lockstep_cycle_register"]
    past_coils = max(m["address"] + 1 for m in where.values() if m["area"] == "coil")
    idle = [Conn(port) for _ in range(10)]
    time.sleep(0.2)
    plc = Conn(port)
    for n in range(1, 6):
        check("PLC writes its output", write_register(plc, fovr, 90)[0] == 6)
        check(f"PLC runs cycle {n}", write_register(plc, cycle, n)[0] == 6)
    monitor = Conn(port)
    check("monitor reads", read_input_registers(monitor, 1000, 2)[:2] == b"\x04\x04")
    for what, reply in [
        ("monitor's register write", write_register(monitor, fovr, 7)),
        ("monitor's event write (EV29)", write_coil(monitor, ev29, True)),
        ("monitor's cycle write", write_register(monitor, cycle, 6)),
    ]:
        check(f"{what} refused with 01", reply == bytes([reply[0], 0x01]) and reply[0] & 0x80,
              reply)
    # What vmt drives lies in the read-only areas: no coil or holding register to write there.
    check("PLC's coil write past the coils: 02", write_coil(plc, past_coils, True) == b"\x85\x02")
    check("PLC's register write to the NC status block: 02",
          write_register(plc, 1000, 1) == b"\x86\x02")
    check("PLC writes the shared event EV29", write_coil(plc, ev29, False)[0] == 5)
    for unit in (0, 255):
        check(f"unit id {unit} is this server", read_input_registers(plc, 1000, 1, unit)[0] == 4)
    check("unit id 7: exception 0B", read_input_registers(plc, 1000, 1, 7) == b"\x84\x0b")
    check("unit id 7 writes nothing", write_register(plc, fovr, 5, 7) == b"\x86\x0b")
    # The idle connections go after the timeout (1 s); the PLC keeps scanning meanwhile.
    deadline = time.monotonic() + 1.6
    n = 6
    while time.monotonic() < deadline:
        check(f"PLC runs cycle {n}", write_register(plc, cycle, n)[0] == 6)
        n += 1
        time.sleep(0.05)
    left = [c for c in idle if not c.closed(2)]
    check("idle connections closed", not left, f"{len(left)} still open")
    check("the PLC's connection stays", write_register(plc, cycle, n)[0] == 6)


def plc_loop(port, fovr, stop):
    c = Conn(port)
    try:
        while not stop.is_set():
            write_register(c, fovr, 100)
            time.sleep(0.01)
    except (ConnectionError, OSError):
        pass
    stop.set()


def flooder(port, stop, counts, i):
    request = struct.pack(">HHHBBHH", 0, 0, 6, 1, 4, 1000, 12)
    reply = 9 + 24
    try:
        c = Conn(port)
        c.sock.sendall(request * 300)
        while not stop.is_set():
            c.recv(reply)
            counts[i] += 1
            c.sock.sendall(request)
    except (ConnectionError, OSError):
        pass


def flood(port, signals, flooders):
    fovr = next(s for s in signals["signals"] if s["name"] == "P00C.FOVR")["modbus"]["address"]
    stop = threading.Event()
    counts = [0] * flooders
    threads = [threading.Thread(target=plc_loop, args=(port, fovr, stop))]
    threads += [threading.Thread(target=flooder, args=(port, stop, counts, i))
                for i in range(flooders)]
    for t in threads:
        t.start()
    stop.wait(60)
    stop.set()
    for t in threads:
        t.join(10)
    print(f"flood: {sum(counts)} replies to {flooders} clients")


def main():
    if sys.argv[1] == "read":
        c = Conn(int(sys.argv[3]), sys.argv[2])
        check("read over " + sys.argv[2], read_input_registers(c, 1000, 1) == b"\x04\x02\x00\x01")
    else:
        port = int(sys.argv[2])
        signals = json.load(open(sys.argv[3]))
        if sys.argv[1] == "access":
            access(port, signals)
        else:
            flood(port, signals, 7 if sys.argv[1] == "flood" else 0)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
