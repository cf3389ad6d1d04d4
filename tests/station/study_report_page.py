#!/usr/bin/python3
"""A study's report in a browser (`vmt view STUDY_DIR --http ...`): click a case, watch it.

    /usr/bin/python3 tests/station/study_report_page.py --url http://127.0.0.1:PORT/report.html

Opens the report in headless chromium, clicks the first case's *watch* link, and checks that the
operator station opens over that case's replay: the 3D view, the time slider, the run's end
reached by the slider. Prints "ok: ..." per check; exits 1 with "FAIL: ..." at the first failed
check, 2 when the browser cannot be started.
"""
import argparse
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from station_page import Failure, dump_console, ok, start_browser, wait_for  # noqa: E402


def run_checks(driver, url):
    from selenium.webdriver.common.by import By
    driver.get(url)
    links = wait_for('the report\'s case links', lambda: driver.find_elements(By.CSS_SELECTOR, 'a.replay'), 20)
    ok('the report lists %d cases to watch' % len(links))
    case = links[0].get_attribute('href')
    links[0].click()  # the server saves the case's run, then redirects to its station
    wait_for('the replay station', lambda: driver.find_elements(By.CSS_SELECTOR, 'canvas[data-view="machine"]'), 60)
    ok('the case opened in the operator station: %s' % driver.current_url)
    pace = wait_for('the model', lambda: driver.execute_script(
        'return fetch("/api/model").then(r => r.json()).then(m => m.pace)'), 20)
    if pace != 'replay':
        raise Failure('the station of %s is a %s, not a replay' % (case, pace))
    slider = wait_for('the time slider', lambda: driver.find_element(By.CSS_SELECTOR, '[data-seek]'), 10)
    wait_for('the slider shown', lambda: slider.is_displayed(), 10)
    end = float(slider.get_attribute('max'))
    if not end > 0:
        raise Failure('the time slider spans %s s' % end)
    # To the end: the replay runs to where the case ended and compares its digest there.
    driver.execute_script(
        'const s = arguments[0]; s.value = s.max; s.dispatchEvent(new Event("input"));'
        's.dispatchEvent(new Event("change"));', slider)
    wait_for('the run state "ended"', lambda: driver.find_element(
        By.CSS_SELECTOR, '[data-run-state]').text.strip() == 'ended', 30)
    ok('the time slider took the case to its end (%.3f s)' % end)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--url', required=True, help="the report's address")
    args = ap.parse_args()
    try:
        driver = start_browser()
    except Exception as e:
        print('FAIL: cannot start chromium/chromedriver: %s' % e, file=sys.stderr)
        return 2
    try:
        run_checks(driver, args.url)
    except Exception as e:
        first = (getattr(e, 'msg', None) or str(e)).strip().splitlines()
        print('FAIL: %s: %s' % (type(e).__name__, first[0] if first else ''), file=sys.stderr)
        dump_console(driver)
        return 1
    finally:
        try:
            driver.quit()
        except Exception:
            pass
    print('ok: all checks passed', flush=True)
    return 0


if __name__ == '__main__':
    sys.exit(main())
