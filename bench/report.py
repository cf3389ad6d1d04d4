#!/usr/bin/env python3
"""The performance report of issue 9: reads the benchmark results in a folder (out/bench/*.json,
as bench/run.sh writes them) and writes report.json (one object, each metric with its value,
unit, source and target) and report.md (one Markdown table).

Usage: report.py [DIR] [--out OUTDIR]   (DIR and OUTDIR default to out/bench)

A missing, malformed or failed input gives its metrics the row "not measured" with the reason:
the report is evidence, never a gate, so it exits 0 whenever it could write both files.
Standard library only: it runs wherever Debian's python3 does, before or without a build.
"""

import json
import math
import os
import statistics
import sys

# Targets come from the issues and the README's aims; a target is (comparison, number, text).
AT_LEAST, AT_MOST = ">=", "<="
DECODE_AIM = (AT_LEAST, 2.5e6, ">= 2.5M (10x LinuxCNC's 200-250k lines/s)")
# "Well under the 4 ms PLC cycle" (README) made a number: a tenth of the cycle.
MODBUS_AIM = (AT_MOST, 400, "<= 400 µs (well under the 4 ms PLC cycle)")


def gbench(source, name, field, metric, unit, target=None, scale=1.0, one_thread=False):
    """A metric read from a Google Benchmark JSON file: `field` is a counter or real_time.
    one_thread: the benchmark runs on its main thread alone, so its rate per second of that
    thread's CPU time is a second value, the one that other processes' load moves least."""
    return dict(kind="gbench", source=source, name=name, field=field, metric=metric, unit=unit,
                target=target, scale=scale, one_thread=one_thread)


def path(source, keys, metric, unit, target=None, missing_note=None):
    """A metric at a key path of a plain JSON file (serve.json, study.json, linuxcnc.json)."""
    return dict(kind="path", source=source, keys=keys, metric=metric, unit=unit, target=target,
                missing_note=missing_note)


def lcnc(program, keys, metric, unit, target=None):
    return path("linuxcnc", ["programs", program] + keys, metric, unit, target)


STUDY_MISSING = "vmt study not built"

# Every metric the issue names, in the order of the table.
METRICS = {
    "realtime_factor_physics": gbench(
        "backend_bench", "physics_lathe_all_axes", "real_time_factor",
        "real-time factor, physics backend (lathe, all axes moving)", "x real time",
        (AT_LEAST, 20, ">= 20x"), one_thread=True),
    "realtime_factor_kinematic": gbench(
        "backend_bench", "kinematic_lathe_all_axes", "real_time_factor",
        "real-time factor, kinematic backend (same motion)", "x real time",
        (AT_LEAST, 2000, ">= 2000x"), one_thread=True),
    "decode_straight_mtc200": gbench(
        "nc_decode_bench", "BM_ParseStraightMtc200", "blocks_per_second",
        "NC decode, straight moves (MTC200, 1M blocks)", "blocks/s", DECODE_AIM, one_thread=True),
    "decode_loops_isg": gbench(
        "nc_decode_bench", "BM_ParseLoopsIsg", "blocks_per_second",
        "NC decode, loops and subprogram calls (ISG)", "blocks/s", DECODE_AIM, one_thread=True),
    "decode_expressions_isg": gbench(
        "nc_decode_bench", "BM_ParseExpressionsIsg", "blocks_per_second",
        "NC decode, expression-heavy (ISG)", "blocks/s", DECODE_AIM, one_thread=True),
    "execute_loops_isg": gbench(
        "nc_decode_bench", "BM_ExecuteLoopsIsg", "executed_blocks_per_second",
        "NC execute, loops/branches/subprograms (ISG)", "executed blocks/s", DECODE_AIM, one_thread=True),
    "execute_loops_mtc200": gbench(
        "nc_decode_bench", "BM_ExecuteLoopsMtc200", "executed_blocks_per_second",
        "NC execute, loops/branches/subprograms (MTC200)", "executed blocks/s", DECODE_AIM, one_thread=True),
    "type5_straight_mtc200": gbench(
        "block_search_bench", "BM_SearchToEndStraightMtc200", "lines_per_second",
        "block search type 5 to the end, straight (MTC200)", "lines/s", DECODE_AIM, one_thread=True),
    "type5_expressions_isg": gbench(
        "block_search_bench", "BM_SearchToEndExpressionsIsg", "lines_per_second",
        "block search type 5 to the end, expressions (ISG)", "lines/s", DECODE_AIM, one_thread=True),
    "type5_loops_isg": gbench(
        "block_search_bench", "BM_SearchToEndLoopsIsg", "lines_per_second",
        "block search type 5 to the end, loops and subprograms (ISG)", "lines/s", DECODE_AIM, one_thread=True),
    "pathguard_checks": gbench(
        "path_guard_bench", "BM_StraightMoveCheckLatheC1", "checks_per_s",
        "PathGuard straight-move checks (lathe-c1 collision parts)", "checks/s",
        (None, None, "a REPOS study's thousands of moves in seconds"), one_thread=True),
    "whole_run_repos_automatic": gbench(
        "whole_run_bench", "BM_WholeRun/repos_automatic/iterations:3", "share_of_backend",
        "whole run / backend alone, repos-automatic (kinematic: NC, PLC, PathGuard, trace)", "",
        (AT_LEAST, 0.30, ">= 0.30")),
    "whole_run_measure_shaft": gbench(
        "whole_run_bench", "BM_WholeRun/measure_shaft/iterations:3", "share_of_backend",
        "whole run / backend alone, measure-shaft (kinematic)", "", (AT_LEAST, 0.30, ">= 0.30")),
    "whole_run_turning": gbench(
        "whole_run_bench", "BM_WholeRun/turning/iterations:2", "share_of_backend",
        "whole run / backend alone, turning (physics)", "", (AT_LEAST, 0.70, ">= 0.70")),
    "whole_run_c_axis_switching": gbench(
        "whole_run_bench", "BM_WholeRun/c_axis_switching/iterations:2", "share_of_backend",
        "whole run / backend alone, c-axis-switching (physics)", "", (AT_LEAST, 0.70, ">= 0.70")),
    "study_cases": path(
        "study", ["cases_per_minute"], "REPOS study cases (vmt study)", "cases/min",
        (AT_LEAST, 1000, ">= 1000"), missing_note=STUDY_MISSING),
    "snapshot_ms": gbench(
        "snapshot_bench", "BM_LatheSnapshot640x480", "real_time",
        "snapshot, lathe-c1 640x480", "ms", (AT_MOST, 20, "<= 20 ms")),
    "render_ms": gbench(
        "render_bench", "BM_Draw640x480/supersample:1", "real_time",
        "render, 640x480, 10k triangles", "ms", (AT_MOST, 20, "<= 20 ms")),
    "modbus_read_us": gbench(
        "modbus_bench", "BM_ModbusReadDiscreteInputs", "round_trip_us",
        "Modbus TCP round trip, read 64 discrete inputs", "µs",
        MODBUS_AIM),
    "modbus_write_us": gbench(
        "modbus_bench", "BM_ModbusWriteCoils", "round_trip_us",
        "Modbus TCP round trip, write 8 coils", "µs",
        MODBUS_AIM),
    "lockstep_cycle_us": gbench(
        "modbus_bench", "BM_LockstepPlcCycle", "round_trip_us",
        "lockstep PLC cycle over Modbus (4 ms of the lathe, kinematic)", "µs",
        (AT_MOST, 4000, "< 4000 µs (faster than real time)")),
    "realtime_lateness_p50": path(
        "serve_realtime", ["cycle_lateness_ms", "p50"],
        "vmt serve --realtime, PLC cycle lateness p50", "ms"),
    "realtime_lateness_p99": path(
        "serve_realtime", ["cycle_lateness_ms", "p99"],
        "vmt serve --realtime, PLC cycle lateness p99", "ms",
        (AT_MOST, 1, "<= 1 ms (well under the 4 ms cycle)")),
    "realtime_lateness_max": path(
        "serve_realtime", ["cycle_lateness_ms", "max"],
        "vmt serve --realtime, PLC cycle lateness max", "ms"),
    "linuxcnc_straight_rs274": lcnc(
        "straight", ["rs274", "lines_per_s"],
        "LinuxCNC rs274 -g, straight program", "lines/s"),
    "linuxcnc_straight_check": lcnc(
        "straight", ["vmt_check", "lines_per_s"],
        "vmt check, same straight program", "lines/s"),
    "linuxcnc_straight_type5": lcnc(
        "straight", ["type5_search", "lines_per_s"],
        "vmt type-5 search (parse + search), same straight program", "lines/s"),
    "linuxcnc_straight_ratio_check": lcnc(
        "straight", ["ratio_check"], "speed-up of vmt check over rs274 (CPU time), straight",
        "x", (AT_LEAST, 10, ">= 10x")),
    "linuxcnc_straight_ratio_type5": lcnc(
        "straight", ["ratio_type5"],
        "speed-up of vmt type-5 search over rs274 (CPU time), straight", "x",
        (AT_LEAST, 10, ">= 10x")),
    "linuxcnc_loops_rs274": lcnc(
        "loops", ["rs274", "lines_per_s"],
        "LinuxCNC rs274 -g, loop program (o-word loops, sub calls)", "lines/s"),
    "linuxcnc_loops_check": lcnc(
        "loops", ["vmt_check", "lines_per_s"],
        "vmt check, same loop program (ISG)", "lines/s"),
    "linuxcnc_loops_type5": lcnc(
        "loops", ["type5_search", "lines_per_s"],
        "vmt type-5 search (parse + search), same loop program", "lines/s"),
    "linuxcnc_loops_ratio_check": lcnc(
        "loops", ["ratio_check"], "speed-up of vmt check over rs274 (CPU time), loops", "x",
        (AT_LEAST, 10, ">= 10x")),
    "linuxcnc_loops_ratio_type5": lcnc(
        "loops", ["ratio_type5"], "speed-up of vmt type-5 search over rs274 (CPU time), loops",
        "x", (AT_LEAST, 10, ">= 10x")),
}

TIME_UNIT_TO_MS = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}


class NotMeasured(Exception):
    """A metric without a value; the message is the reason shown in the report."""


def load_sources(folder, names):
    """Each source file parsed once: name -> object, or name -> NotMeasured (the reason)."""
    loaded = {}
    for name in names:
        file = os.path.join(folder, name + ".json")
        try:
            with open(file, encoding="utf-8") as f:
                loaded[name] = json.load(f)
        except FileNotFoundError:
            loaded[name] = NotMeasured("no " + name + ".json")
        except (OSError, UnicodeDecodeError, json.JSONDecodeError) as e:
            loaded[name] = NotMeasured("malformed " + name + ".json: " + str(e).splitlines()[0])
    return loaded


def number(value, what):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise NotMeasured(what + " is not a number")
    return float(value)


def gbench_value(data, spec):
    """The median over the runs of one benchmark (several with --benchmark_repetitions)."""
    benchmarks = data.get("benchmarks") if isinstance(data, dict) else None
    if not isinstance(benchmarks, list):
        raise NotMeasured("no benchmarks list in " + spec["source"] + ".json")
    # UseRealTime() appends "/real_time" to the name; the report's names are without it.
    names = (spec["name"], spec["name"] + "/real_time")
    runs = [b for b in benchmarks if isinstance(b, dict) and b.get("run_type", "iteration")
            == "iteration" and b.get("run_name", b.get("name")) in names]
    if not runs:
        raise NotMeasured(spec["name"] + " not in " + spec["source"] + ".json")
    failed = [b for b in runs if b.get("error_occurred")]
    if failed:
        raise NotMeasured(spec["name"] + " failed: " + str(failed[0].get("error_message", "")))
    values, per_cpu = [], []
    for b in runs:
        value = number(b.get(spec["field"]), spec["name"] + " " + spec["field"])
        if spec["field"] == "real_time":
            unit = b.get("time_unit", "ns")
            if unit not in TIME_UNIT_TO_MS:
                raise NotMeasured(spec["name"] + ": unknown time unit " + str(unit))
            value *= TIME_UNIT_TO_MS[unit]
        values.append(value * spec["scale"])
        # A rate counter over real time, rescaled to the main thread's CPU time.
        real, cpu = b.get("real_time"), b.get("cpu_time")
        if (spec["one_thread"] and isinstance(real, (int, float))
                and isinstance(cpu, (int, float)) and real > 0 and cpu > 0):
            per_cpu.append(value * spec["scale"] * real / cpu)
    return statistics.median(values), (statistics.median(per_cpu) if per_cpu else None)


def path_value(data, spec):
    node = data
    for key in spec["keys"]:
        if not isinstance(node, dict) or key not in node:
            reason = data.get("reason") if isinstance(data, dict) else None
            if isinstance(reason, str) and reason:
                raise NotMeasured(reason)
            raise NotMeasured("no " + ".".join(spec["keys"]) + " in " + spec["source"] + ".json")
        node = node[key]
    return number(node, ".".join(spec["keys"]))


def study_value(data, spec):
    """study.json may carry cases_per_minute, or cases and wall_s to derive it from."""
    if isinstance(data, dict) and "cases_per_minute" not in data and "cases" in data:
        cases, wall_s = number(data.get("cases"), "cases"), number(data.get("wall_s"), "wall_s")
        if wall_s <= 0:
            raise NotMeasured("study.json: wall_s is not positive")
        return cases / wall_s * 60
    return path_value(data, spec)


def source_label(spec):
    if spec["kind"] == "gbench":
        return "%s.json: %s %s" % (spec["source"], spec["name"], spec["field"])
    return "%s.json: %s" % (spec["source"], ".".join(spec["keys"]))


def meets(value, target):
    if value is None or target is None or target[0] is None:
        return None
    return value >= target[1] if target[0] == AT_LEAST else value <= target[1]


def build_report(folder):
    sources = load_sources(folder, sorted({s["source"] for s in METRICS.values()}))
    metrics = {}
    for key, spec in METRICS.items():
        value, value_cpu, note = None, None, None
        data = sources[spec["source"]]
        try:
            if isinstance(data, NotMeasured):
                if spec.get("missing_note") and str(data).startswith("no "):
                    raise NotMeasured(spec["missing_note"])
                raise data
            if spec["kind"] == "gbench":
                value, value_cpu = gbench_value(data, spec)
            elif spec["source"] == "study":
                value = study_value(data, spec)
            else:
                value = path_value(data, spec)
        except NotMeasured as e:
            note = str(e)
        except (ArithmeticError, AttributeError, KeyError, TypeError, ValueError) as e:
            # A shape no check above foresaw: still a row, never a crash.
            value, value_cpu, note = None, None, "unreadable %s.json: %r" % (spec["source"], e)
        target = spec["target"]
        metrics[key] = {
            "metric": spec["metric"],
            "value": value,
            "value_per_cpu_s": value_cpu,
            "unit": spec["unit"],
            "source": source_label(spec),
            "target": target[2] if target else None,
            "meets_target": meets(value, target),
        }
        if note is not None:
            metrics[key]["not_measured"] = note
    return {"folder": folder, "load_average_1min": load_averages(sources), "metrics": metrics}


def load_averages(sources):
    """The 1-minute load average each result was taken under (Google Benchmark's context, the
    LinuxCNC comparison's own): wall-time numbers on a 2-core machine that builds mean little."""
    loads = {}
    for name, data in sources.items():
        if not isinstance(data, dict):
            continue
        context = data.get("context")
        load = context.get("load_avg") if isinstance(context, dict) else None
        if isinstance(load, list) and load and isinstance(load[0], (int, float)):
            loads[name] = round(float(load[0]), 2)
        elif isinstance(data.get("load_average_1min_at_start"), (int, float)):
            loads[name] = round(float(data["load_average_1min_at_start"]), 2)
    return loads


def format_value(value):
    """Three significant digits, k and M for large rates: 5.9M reads better than 5903123.4."""
    if value is None:
        return None
    magnitude = abs(value)
    if magnitude >= 1e6:
        return "%.3gM" % (value / 1e6)
    if magnitude >= 1e4:
        return "%.3gk" % (value / 1e3)
    if magnitude >= 100:
        return "%.0f" % value
    return "%.3g" % value


def markdown(report):
    lines = ["| metric | value | on CPU time | unit | target | meets |",
             "| --- | --- | --- | --- | --- | --- |"]
    for m in report["metrics"].values():
        value = format_value(m["value"])
        if value is None:
            value = "not measured (%s)" % m["not_measured"]
        verdict = {True: "yes", False: "**no**", None: ""}[m["meets_target"]]
        cells = [m["metric"], value, format_value(m["value_per_cpu_s"]) or "", m["unit"],
                 m["target"] or "", verdict]
        lines.append("| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |")
    loads = report["load_average_1min"]
    if loads:
        lines += ["", "Load average (1 min) at the start of each: " +
                  ", ".join("%s %.2f" % item for item in sorted(loads.items())) +
                  " (cores: %d)." % (os.cpu_count() or 0)]
    return "\n".join(lines) + "\n"


def main(argv):
    args = argv[1:]
    out = None
    if "--out" in args:
        i = args.index("--out")
        if i + 1 >= len(args):
            print(__doc__.strip().splitlines()[3], file=sys.stderr)
            return 2
        out = args[i + 1]
        del args[i:i + 2]
    if len(args) > 1 or any(a.startswith("-") for a in args):
        print(__doc__.strip().splitlines()[3], file=sys.stderr)
        return 2
    folder = args[0] if args else os.path.join("out", "bench")
    out = out or folder
    report = build_report(folder)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "report.json"), "w", encoding="utf-8") as f:
        json.dump(report, f, indent=2, ensure_ascii=False)
        f.write("\n")
    with open(os.path.join(out, "report.md"), "w", encoding="utf-8") as f:
        f.write(markdown(report))
    measured = sum(m["value"] is not None for m in report["metrics"].values())
    print("report: %d of %d metrics measured -> %s/report.{json,md}"
          % (measured, len(report["metrics"]), out))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
