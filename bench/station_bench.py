#!/usr/bin/env python3
"""What streaming to the operator station costs the simulation.

Runs `vmt serve SCENE --http` as fast as the machine allows (run at speed 0) twice, alternately
several times: once with no page connected, once with PAGES simulated pages, each polling
/api/state as a browser does (the next request as soon as the last answer arrived, at most 30 a
second), the signals 2.5 times a second and the events 4 times a second. Prints JSON: the
simulated seconds per wall second of each run, their medians and the cost in percent.

Usage: bench/station_bench.py [--vmt build/sim/vmt] [--scene scenes/station.yaml]
       [--until 300] [--pages 5] [--pairs 3]
"""
import argparse
import json
import os
import re
import signal
import statistics
import subprocess
import tempfile
import threading
import time
import urllib.request


def get(url):
    with urllib.request.urlopen(url, timeout=10) as r:
        return r.read()


def post(url, body):
    req = urllib.request.Request(url, data=json.dumps(body).encode(),
                                 headers={"Content-Type": "application/json"})
    with urllib.request.urlopen(req, timeout=10) as r:
        return r.read()


def page(base, stop):
    """One browser's polling: state at most 30/s, signals 2.5/s, events 4/s."""
    next_signals = next_events = 0.0
    events = 0
    while not stop.is_set():
        start = time.monotonic()
        state = json.loads(get(base + "/api/state"))
        if start >= next_signals:
            get(base + "/api/signals")
            next_signals = start + 0.4
        if start >= next_events and state.get("events", 0) > events:
            events = json.loads(get(base + f"/api/events?from={events}"))["total"]
            next_events = start + 0.25
        time.sleep(max(0.0, 1 / 30 - (time.monotonic() - start)))


def one_run(args, pages):
    out = tempfile.mkdtemp(prefix="station-bench-")
    proc = subprocess.Popen([args.vmt, "serve", args.scene, "--http", "127.0.0.1:0", "--until",
                             str(args.until), "--out", out],
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    base = None
    for line in proc.stdout:
        m = re.search(r"operator station on (http://127\.0\.0\.1:\d+)/", line)
        if m:
            base = m.group(1)
            break
    stop = threading.Event()
    threads = [threading.Thread(target=page, args=(base, stop)) for _ in range(pages)]
    for t in threads:
        t.start()
    time.sleep(0.5)  # the pages are polling before the run starts
    start = time.monotonic()
    post(base + "/api/run", {"action": "run", "speed": 0})
    while json.loads(get(base + "/api/state"))["run"] != "ended":
        time.sleep(0.05)
    wall = time.monotonic() - start
    stop.set()
    for t in threads:
        t.join()
    proc.send_signal(signal.SIGINT)
    proc.wait(timeout=60)
    return args.until / wall


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--vmt", default="build/sim/vmt")
    p.add_argument("--scene", default="scenes/station.yaml")
    p.add_argument("--until", type=float, default=300)
    p.add_argument("--pages", type=int, default=5)
    p.add_argument("--pairs", type=int, default=3)
    args = p.parse_args()
    alone, watched = [], []
    for _ in range(args.pairs):
        alone.append(one_run(args, 0))
        watched.append(one_run(args, args.pages))
    a, w = statistics.median(alone), statistics.median(watched)
    print(json.dumps({"benchmark": "station", "scene": args.scene, "simulated_s": args.until,
                      "pages": args.pages, "real_time_factor_alone": alone,
                      "real_time_factor_watched": watched, "median_alone": a,
                      "median_watched": w, "cost_percent": round(100 * (1 - w / a), 1),
                      "cores": os.cpu_count()}))


if __name__ == "__main__":
    main()
