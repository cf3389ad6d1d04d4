#!/usr/bin/env python3
"""How a study's merge and report grow with its number of cases, without running the cases.

Takes the case results of a real study (a cases.jsonl, the template), writes synthetic studies
of N cases as 100 shard folders the way `vmt study repos --shard K/100` leaves them (each
shard's cases.jsonl in case id order, whole interruption groups per shard), then times
`vmt study merge` of the shards (the streaming merge and report.html with its case pages) under
/usr/bin/time -v (wall time, peak memory) and report.html's load in headless Chromium.
Prints JSON: one record per size.

    bench/study_scale.py --template out/bench/study/cases.jsonl --cases 1000,10000,100000

Without --template it runs a small real study first (scenes/study-repos-turning.yaml, 200
cases). What it measures is the merge and the report, not the cases: a real study of N cases
costs N / (cases per minute) on top (bench/study.sh).
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def template_lines(args):
    path = args.template
    if not path:
        out = os.path.join(args.work, "template")
        shutil.rmtree(out, ignore_errors=True)
        subprocess.run([args.vmt, "study", "repos", "scenes/study-repos-turning.yaml", "--out",
                        out, "--jobs", "2", "--max-cases", "200", "--snapshots", "0"],
                       cwd=ROOT, check=True, stdout=subprocess.DEVNULL)
        path = os.path.join(out, "cases.jsonl")
    with open(path, encoding="utf-8") as f:
        lines = [l.rstrip("\n") for l in f if l.strip()]
    if not lines:
        sys.exit(f"{path}: no cases")
    return lines, os.path.dirname(path)


def write_shards(lines, template_dir, n, shards, folder):
    """Case i is template line i % len(lines) with the interruption point p<i // group>; the
    groups (one point, all its retracts and modes) dealt to the shards in turn."""
    shutil.rmtree(folder, ignore_errors=True)
    group = 8
    by_shard = [[] for _ in range(shards)]
    cases = [json.loads(l) for l in lines]
    for i in range(n):
        k = i % len(lines)
        c = cases[k]
        # The interruption point pNNNNNNN.K in the id and its "interrupt" field, so that the case
        # is found by its fields as by its id (vmt study compare matches cases so).
        label = f"p{i // group:07d}.{i % group}"
        new = f"{c['subroutine']}/{label}/{c['retract']}/{c['mode']}"
        dump = lambda v: json.dumps(v, ensure_ascii=False, separators=(",", ":"))
        line = lines[k].replace(dump(c["case"]), dump(new), 1).replace(
            '"interrupt":' + dump(c["interrupt"]), '"interrupt":' + dump(label), 1)
        by_shard[(i // group) % shards].append((new, line))
    for s, cases in enumerate(by_shard, 1):
        d = os.path.join(folder, f"shard-{s:03d}")
        os.makedirs(d)
        cases.sort(key=lambda c: c[0].encode("utf-8"))
        with open(os.path.join(d, "cases.jsonl"), "w", encoding="utf-8") as f:
            f.writelines(line + "\n" for _, line in cases)
        ref = os.path.join(template_dir, "reference.json")
        if os.path.exists(ref):
            shutil.copy(ref, d)
    return [os.path.join(folder, f"shard-{s:03d}") for s in range(1, shards + 1)]


def timed(cmd):
    """Wall seconds and peak resident memory (MB) of cmd, from /usr/bin/time -v."""
    r = subprocess.run(["/usr/bin/time", "-v"] + cmd, cwd=ROOT, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"{' '.join(cmd[:3])}...: {r.stderr[-2000:]}")
    rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", r.stderr).group(1))
    wall = re.search(r"Elapsed \(wall clock\) time.*: (?:(\d+):)?(\d+):([\d.]+)", r.stderr)
    h, m, s = wall.groups()
    return int(h or 0) * 3600 + int(m) * 60 + float(s), rss / 1024


def browser_load_s(chromium, page):
    """Seconds from asking headless Chromium for `page` to the first page of cases in its table
    (the page's script loads it from cases-pages/), in a browser already started (Selenium and
    chromedriver: Debian's python3-selenium, chromium-driver; run this script with
    /usr/bin/python3). Without Selenium: `chromium --dump-dom` of the page less the same for an
    empty page, which also counts the browser's start and shutdown. Best of three."""
    try:
        from selenium import webdriver
        from selenium.webdriver.chrome.options import Options
        from selenium.webdriver.chrome.service import Service
    except ImportError:
        webdriver = None
    if webdriver and os.path.exists("/usr/bin/chromedriver"):
        options = Options()
        options.binary_location = chromium
        for a in ("--headless", "--no-sandbox", "--disable-gpu"):
            options.add_argument(a)
        driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
        try:
            driver.get("about:blank")
            best = None
            for _ in range(3):
                driver.get("about:blank")
                t = time.monotonic()
                driver.get("file://" + page)
                filled = False
                while time.monotonic() - t < 60 and not filled:
                    filled = driver.execute_script(
                        "return document.querySelector('#rows tr') !== null")
                    if not filled:
                        time.sleep(0.01)
                elapsed = time.monotonic() - t
                best = elapsed if best is None else min(best, elapsed)
            return best, 0.0, filled
        finally:
            driver.quit()

    def run(url):
        t = time.monotonic()
        dom = subprocess.run([chromium, "--headless", "--no-sandbox", "--disable-gpu",
                              "--dump-dom", url], capture_output=True, text=True,
                             timeout=120).stdout
        return time.monotonic() - t, dom
    blank = os.path.join(os.path.dirname(page), "blank.html")
    with open(blank, "w") as f:
        f.write("<!DOCTYPE html><html><body></body></html>\n")
    base = min(run("file://" + blank)[0] for _ in range(3))
    best, filled = None, False
    for _ in range(3):
        t, dom = run("file://" + page)
        best = t if best is None else min(best, t)
        filled = filled or '<tbody id="rows"><tr>' in dom
    return max(best - base, 0.0), base, filled


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--vmt", default=os.path.join(ROOT, "build/sim/vmt"))
    p.add_argument("--template", help="a real study's cases.jsonl")
    p.add_argument("--cases", default="1000,10000,100000")
    p.add_argument("--shards", type=int, default=100)
    p.add_argument("--work", default=os.path.join(ROOT, "out/bench/study_scale"))
    p.add_argument("--chromium", default=shutil.which("chromium") or "")
    p.add_argument("--keep", action="store_true", help="keep the shards and merged folders")
    args = p.parse_args()
    os.makedirs(args.work, exist_ok=True)
    lines, template_dir = template_lines(args)
    for n in [int(x) for x in args.cases.split(",")]:
        folder = os.path.join(args.work, f"n{n}")
        dirs = write_shards(lines, template_dir, n, args.shards, os.path.join(folder, "shards"))
        out = os.path.join(folder, "merged")
        shutil.rmtree(out, ignore_errors=True)
        wall, rss = timed([args.vmt, "study", "merge"] + dirs + ["--out", out])
        report = os.path.join(out, "report.html")
        pages = len(os.listdir(os.path.join(out, "cases-pages")))
        rec = {
            "cases": n,
            "shards": args.shards,
            "template_cases": len(lines),
            "merge_and_report_wall_s": round(wall, 2),
            "peak_rss_mb": round(rss, 1),
            "cases_jsonl_mb": round(os.path.getsize(os.path.join(out, "cases.jsonl")) / 2**20, 1),
            "report_html_kb": round(os.path.getsize(report) / 1024, 1),
            "case_pages": pages,
        }
        if args.chromium:
            load, base, filled = browser_load_s(args.chromium, report)
            rec.update({"report_load_s": round(load, 2), "browser_start_s": round(base, 2),
                        "first_page_shown": filled})
        print(json.dumps(rec), flush=True)
        if not args.keep:
            shutil.rmtree(os.path.join(folder, "shards"), ignore_errors=True)


if __name__ == "__main__":
    main()
