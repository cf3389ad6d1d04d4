#!/usr/bin/env python3
"""vmt against LinuxCNC's interpreter on the same generated programs (issue 9).

Usage: linuxcnc_compare.py [--build DIR] [--out DIR] [--blocks N] [--repeat R] [--rs274 PATH]

Writes the straight and the loop program of the NC benchmarks (bench/generated_programs.hpp) as
files twice, in vmt's dialect (MTC200 / ISG) and in RS274NGC, and times whole processes on them:
`rs274 -g FILE` (LinuxCNC's stand-alone interpreter, Debian package linuxcnc-uspace), `vmt check
FILE` (parse) and `search_program FILE` (parse and block search type 5 to the program end). Each
side's speed is its file's source lines per second of CPU time (user + system of the process,
best of R runs): the machine is shared with builds, and CPU time moves least under their load.
The ratios are rs274's CPU time over vmt's on the same moves. Writes DIR/linuxcnc.json (default
out/bench).

Without rs274 it says so, writes linuxcnc.json with the reason, and exits 0: CI does not install
LinuxCNC. Exit 2 when vmt's own tools are not built, 1 when a tool fails on a program.
"""

import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import time


def run_timed(cmd, stdout=subprocess.DEVNULL):
    """Runs cmd; returns (wall_s, cpu_s, captured stdout or None). Raises on a non-zero exit."""
    # The children's rusage grows by exactly this child's: one runs at a time.
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=stdout, stderr=subprocess.PIPE)
    out, err = proc.communicate()
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        raise RuntimeError("%s exited %d: %s" % (" ".join(cmd), proc.returncode,
                                                 err.decode(errors="replace").strip()[:500]))
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, out


def best_of(repeat, cmd, stdout=subprocess.DEVNULL):
    runs = [run_timed(cmd, stdout) for _ in range(repeat)]
    return min(runs, key=lambda r: r[1])


def count_lines(file):
    with open(file, "rb") as f:
        return sum(chunk.count(b"\n") for chunk in iter(lambda: f.read(1 << 20), b""))


def speed(lines, wall, cpu):
    return {"wall_s": round(wall, 4), "cpu_s": round(cpu, 4),
            "lines_per_s": round(lines / cpu, 1) if cpu > 0 else None}


def write_json(out_dir, obj):
    os.makedirs(out_dir, exist_ok=True)
    file = os.path.join(out_dir, "linuxcnc.json")
    with open(file, "w", encoding="utf-8") as f:
        json.dump(obj, f, indent=2)
        f.write("\n")
    return file


def linuxcnc_version():
    try:
        return subprocess.run(["dpkg-query", "-W", "-f=${Version}", "linuxcnc-uspace"],
                              capture_output=True, text=True, check=False).stdout or None
    except OSError:
        return None


def compare(program, args, tools, work):
    """One program: generate both files, time the three tools, return the linuxcnc.json part."""
    generate, search, vmt, rs274 = tools
    files = {}
    for dialect, name in (("vmt", program + ".nc"), ("rs274ngc", program + ".ngc")):
        files[dialect] = os.path.join(work, name)
        with open(files[dialect], "wb") as f:
            subprocess.run([generate, program, "--dialect", dialect, "--blocks", str(args.blocks)],
                           stdout=f, check=True)
    vmt_files = [files["vmt"]]
    if program == "loops":  # ISG's subprogram is its own program; RS274NGC has it inside
        vmt_files.append(os.path.join(work, "sub_a.nc"))
        with open(vmt_files[1], "wb") as f:
            subprocess.run([generate, "loops-sub"], stdout=f, check=True)
    lines_vmt, lines_ngc = count_lines(files["vmt"]), count_lines(files["rs274ngc"])

    wall, cpu, _ = best_of(args.repeat, [rs274, "-g", files["rs274ngc"], os.devnull])
    result = {"vmt_file_lines": lines_vmt, "rs274_file_lines": lines_ngc,
              "rs274": speed(lines_ngc, wall, cpu)}
    wall, cpu, _ = best_of(args.repeat, [vmt, "check", files["vmt"]])
    result["vmt_check"] = speed(lines_vmt, wall, cpu)
    wall, cpu, out = best_of(args.repeat, [search] + vmt_files, subprocess.PIPE)
    result["type5_search"] = speed(lines_vmt, wall, cpu)
    result["type5_search"]["phases"] = json.loads(out)
    # Same moves, so the ratio is of times: RS274NGC needs more lines for the same loops (no
    # $FOR), and a ratio of lines/s would count that against vmt.
    for key, tool in (("ratio_check", "vmt_check"), ("ratio_type5", "type5_search")):
        mine, theirs = result[tool]["cpu_s"], result["rs274"]["cpu_s"]
        result[key] = round(theirs / mine, 2) if mine > 0 else None
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    parser.add_argument("--build", default="build", help="vmt's build folder (default: build)")
    parser.add_argument("--out", default=os.path.join("out", "bench"))
    parser.add_argument("--blocks", type=int, default=1000000,
                        help="program length (default: 1M blocks, as the benchmarks)")
    parser.add_argument("--repeat", type=int, default=3, help="runs per tool, best kept")
    parser.add_argument("--rs274", default="rs274", help="LinuxCNC's rs274 (default: on PATH)")
    args = parser.parse_args()
    if args.blocks < 10 or args.repeat < 1:
        parser.error("--blocks must be >= 10 and --repeat >= 1")

    rs274 = shutil.which(args.rs274)
    if rs274 is None:
        reason = "rs274 not installed (Debian package linuxcnc-uspace)"
        print("linuxcnc_compare: %s: LinuxCNC comparison skipped" % reason)
        write_json(args.out, {"measured": False, "reason": reason})
        return 0
    tools = [os.path.join(args.build, "bench", "generate_program"),
             os.path.join(args.build, "bench", "search_program"),
             os.path.join(args.build, "sim", "vmt")]
    missing = [t for t in tools if not os.access(t, os.X_OK)]
    if missing:
        print("linuxcnc_compare: not built: " + ", ".join(missing), file=sys.stderr)
        return 2

    work = os.path.join(args.out, "linuxcnc")
    os.makedirs(work, exist_ok=True)
    report = {"measured": True, "rs274": rs274, "linuxcnc_version": linuxcnc_version(),
              "blocks": args.blocks, "repeat": args.repeat,
              "basis": "lines/s: source lines of each tool's own file per CPU second (user + "
                       "system) of the whole process, best of repeat; ratio: rs274 CPU s / "
                       "vmt CPU s on the same moves",
              "cores": os.cpu_count(), "load_average_1min_at_start": os.getloadavg()[0],
              "programs": {}}
    try:
        for program in ("straight", "loops"):
            report["programs"][program] = compare(program, args, tools + [rs274], work)
            p = report["programs"][program]
            print("%-8s rs274 %.0f lines/s, vmt check %.0f (%.1fx), type-5 search %.0f (%.1fx)"
                  % (program, p["rs274"]["lines_per_s"], p["vmt_check"]["lines_per_s"],
                     p["ratio_check"], p["type5_search"]["lines_per_s"], p["ratio_type5"]))
    except (RuntimeError, subprocess.CalledProcessError, ValueError) as e:
        print("linuxcnc_compare: %s" % e, file=sys.stderr)
        write_json(args.out, {"measured": False, "reason": "failed: %s" % str(e)[:300]})
        return 1
    finally:
        shutil.rmtree(work, ignore_errors=True)  # 1M-block programs: tens of MB each
    report["load_average_1min_at_end"] = os.getloadavg()[0]
    print("-> " + write_json(args.out, report))
    return 0


if __name__ == "__main__":
    sys.exit(main())
