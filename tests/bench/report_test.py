#!/usr/bin/env python3
"""The performance report (bench/report.py) on the small result files of fixture/, and the
LinuxCNC comparison (bench/linuxcnc_compare.py) without rs274 and, where LinuxCNC is installed,
on short programs. Usage: report_test.py SOURCE_DIR BUILD_DIR"""

import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

SRC, BUILD = sys.argv[1], sys.argv[2]
REPORT = os.path.join(SRC, "bench", "report.py")
COMPARE = os.path.join(SRC, "bench", "linuxcnc_compare.py")
FIXTURE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "fixture")


def run(*cmd):
    return subprocess.run([sys.executable, *cmd], capture_output=True, text=True, timeout=600)


class ReportTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="vmt_report_test_")

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def report(self, folder):
        r = run(REPORT, folder, "--out", self.tmp)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(self.tmp, "report.json"), encoding="utf-8") as f:
            report = json.load(f)
        with open(os.path.join(self.tmp, "report.md"), encoding="utf-8") as f:
            md = f.read()
        return report["metrics"], md

    def test_fixture_values_and_reasons(self):
        m, md = self.report(FIXTURE)
        self.assertEqual(m["realtime_factor_physics"]["value"], 41.0)
        self.assertTrue(m["realtime_factor_physics"]["meets_target"])
        self.assertEqual(m["realtime_factor_physics"]["unit"], "x real time")
        self.assertIn("backend_bench.json", m["realtime_factor_physics"]["source"])
        self.assertFalse(m["realtime_factor_kinematic"]["meets_target"])  # 1500 < 2000
        # The rate per second of the benchmark thread's CPU time: 41 x 24.4 ms / 24.3 ms.
        self.assertAlmostEqual(m["realtime_factor_physics"]["value_per_cpu_s"], 41 * 24.4 / 24.3)
        self.assertIsNone(m["realtime_lateness_p99"]["value_per_cpu_s"])
        # Repetitions: the median of the iteration runs; the aggregate rows are not runs.
        self.assertEqual(m["decode_straight_mtc200"]["value"], 6.0e6)
        # Google Benchmark's time unit is converted: 11.3e6 ns is 11.3 ms.
        self.assertAlmostEqual(m["snapshot_ms"]["value"], 11.3)
        self.assertEqual(m["realtime_lateness_p99"]["value"], 0.56)
        # A failed benchmark, a counter that is no number, a missing benchmark.
        self.assertIn("unexpected $ENDIF", m["decode_loops_isg"]["not_measured"])
        self.assertIn("not a number", m["decode_expressions_isg"]["not_measured"])
        self.assertIn("BM_ExecuteLoopsIsg not in", m["execute_loops_isg"]["not_measured"])
        # A malformed file (block_search_bench.json is cut off), a wrong shape, a missing file.
        self.assertIn("malformed block_search_bench.json",
                      m["type5_straight_mtc200"]["not_measured"])
        self.assertIn("no benchmarks list", m["pathguard_checks"]["not_measured"])
        self.assertIn("no modbus_bench.json", m["modbus_read_us"]["not_measured"])
        # study.json is optional until vmt study exists; linuxcnc.json carries its own reason.
        self.assertEqual(m["study_cases"]["not_measured"], "vmt study not built")
        self.assertIn("rs274 not installed", m["linuxcnc_straight_ratio_check"]["not_measured"])
        for key in ("decode_loops_isg", "type5_loops_isg", "study_cases"):
            self.assertIsNone(m[key]["value"])
            self.assertIsNone(m[key]["meets_target"])
        # One Markdown table: a header, a rule, a row per metric.
        rows = md.strip().splitlines()
        self.assertEqual(rows[0], "| metric | value | on CPU time | unit | target | meets |")
        self.assertEqual(len(rows), 2 + len(m) + 2)  # and the load averages below it
        self.assertIn("Load average (1 min) at the start of each: backend_bench 1.50 (cores", md)
        self.assertIn("| not measured (vmt study not built) |  | cases/min | >= 1000 |", md)
        self.assertIn("| 41 | 41.2 | x real time | >= 20x | yes |", md)
        self.assertIn("| 1500 | 1500 | x real time | >= 2000x | **no** |", md)

    def test_empty_folder_reports_every_metric_not_measured(self):
        empty = os.path.join(self.tmp, "empty")
        os.makedirs(empty)
        m, md = self.report(empty)
        self.assertTrue(all(v["value"] is None for v in m.values()))
        self.assertEqual(md.count("not measured"), len(m))
        self.assertNotIn("Load average", md)

    def test_study_from_cases_and_wall_time(self):
        folder = os.path.join(self.tmp, "study")
        os.makedirs(folder)
        with open(os.path.join(folder, "study.json"), "w", encoding="utf-8") as f:
            json.dump({"cases": 500, "wall_s": 20.0}, f)
        m, _ = self.report(folder)
        self.assertEqual(m["study_cases"]["value"], 1500.0)
        self.assertTrue(m["study_cases"]["meets_target"])

    def test_bad_usage(self):
        self.assertEqual(run(REPORT, "a", "b").returncode, 2)
        self.assertEqual(run(REPORT, "--out").returncode, 2)


class LinuxcncCompareTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="vmt_linuxcnc_test_")

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def compare(self, *args):
        r = run(COMPARE, "--build", BUILD, "--out", self.tmp, *args)
        with open(os.path.join(self.tmp, "linuxcnc.json"), encoding="utf-8") as f:
            return r, json.load(f)

    def test_without_rs274_says_so_and_exits_0(self):
        r, result = self.compare("--rs274", os.path.join(self.tmp, "no-rs274"))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("rs274 not installed", r.stdout)
        self.assertFalse(result["measured"])

    @unittest.skipIf(shutil.which("rs274") is None, "LinuxCNC (linuxcnc-uspace) not installed")
    @unittest.skipIf(not os.path.exists(os.path.join(BUILD, "bench", "search_program")),
                     "benchmarks not built (VMT_BUILD_BENCH=OFF)")
    def test_short_programs_through_rs274_and_vmt(self):
        r, result = self.compare("--blocks", "2000", "--repeat", "1")
        self.assertEqual(r.returncode, 0, r.stderr)
        for program, vmt_lines in (("straight", 2000), ("loops", 2001)):
            p = result["programs"][program]
            self.assertEqual(p["vmt_file_lines"], vmt_lines)
            for tool in ("rs274", "vmt_check", "type5_search"):
                self.assertGreater(p[tool]["lines_per_s"], 0)
            self.assertGreater(p["ratio_check"], 0)
        # The search read the loops as often as they run: 10 passes of each loop body.
        loops = result["programs"]["loops"]["type5_search"]["phases"]
        self.assertGreater(loops["decoder_lines"], 5 * loops["source_lines"])
        # The RS274NGC twins make the moves of vmt's programs: 2000 straight feeds each (the loop
        # program: 200 loops of 10 passes, one of them the subprogram's move).
        for program in ("straight", "loops"):
            ngc = os.path.join(self.tmp, program + ".ngc")
            with open(ngc, "wb") as f:
                subprocess.run([os.path.join(BUILD, "bench", "generate_program"), program,
                                "--dialect", "rs274ngc", "--blocks", "2000"], stdout=f, check=True)
            canon = os.path.join(self.tmp, program + ".canon")
            subprocess.run(["rs274", "-g", ngc, canon], capture_output=True, check=True)
            with open(canon, encoding="utf-8") as f:
                self.assertEqual(f.read().count("STRAIGHT_FEED("), 2000, program)
        # The work files (tens of MB at 1M blocks) are gone.
        self.assertFalse(os.path.exists(os.path.join(self.tmp, "linuxcnc")))


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0]], verbosity=2)
