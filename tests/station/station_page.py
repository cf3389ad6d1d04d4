#!/usr/bin/python3
"""Smoke test of the operator station's page against a running `vmt serve` (or a mock).

    /usr/bin/python3 tests/station/station_page.py --url http://127.0.0.1:PORT/ --screenshot OUT.png
        [--jog-key mJGPOS_X --jog-axis X] [--manual-key mMANU] [--auto-key mAUTO --start-key mSTART]
        [--seek T]   (a replay of vmt view: the time slider goes to T, the keys are disabled)
        [--golden PNG --vmt VMT [--golden-out DIR] [--refresh-golden]]

With --golden, the 3D view right after the page loaded (a lockstep run, paused at t = 0, the
first camera, the view pinned to GOLDEN_W x GOLDEN_H, the tool path trail empty) is compared
with PNG by `VMT imgdiff`; a failure names the actual picture and the difference picture
(in --golden-out). After an intended change of the view, --refresh-golden writes PNG instead
(tests/cli/station_test.sh passes it when VMT_REFRESH_STATION_GOLDEN=1); look at the picture
before committing it.

Drives Debian's chromium through chromedriver (selenium 4), headless with SwiftShader so that
WebGL renders without a GPU. Prints one "ok: ..." line per check; exits 1 with "FAIL: ..." at
the first failed check, 2 when the browser cannot be started. Every wait is bounded; the whole
run stays under 90 s.
"""
import argparse
import base64
import os
import shutil
import struct
import subprocess
import sys
import time
import zlib

DEADLINE_S = 85.0
START = time.monotonic()


class Failure(Exception):
    pass


def remaining():
    return DEADLINE_S - (time.monotonic() - START)


def wait_for(what, predicate, timeout, interval=0.05):
    """predicate() -> a true value when done; returns it, raises Failure on timeout."""
    end = time.monotonic() + min(timeout, max(0.5, remaining()))
    last_error = None
    while True:
        try:
            value = predicate()
            if value:
                return value
        except Exception as e:  # a stale element, a value not yet parseable
            last_error = e
        if time.monotonic() >= end:
            raise Failure('timed out after %.1f s waiting for %s%s' % (
                timeout, what, ' (last error: %s)' % last_error if last_error else ''))
        time.sleep(interval)


def ok(text):
    print('ok: ' + text, flush=True)


# The 3D view's size for the golden, whatever the page's layout makes of the window.
GOLDEN_W, GOLDEN_H = 960, 540
# SwiftShader draws the same bytes run after run on one machine: six runs gave equal PNGs
# (0 pixels beyond 0 levels). Another CPU may get other code from SwiftShader's JIT, which
# moves edge pixels by a few levels, as llvmpipe's goldens allow for (render/
# image_compare.hpp: at most 0.021 % of the pixels beyond 2 levels). So at most 0.03 % of the
# pixels (155) may differ by more than 8 levels. What that still catches, measured on this
# view: the Z carriage 2 mm off changes 301 pixels, the turret 1 degree off 713, the camera's
# field of view 0.5 degree wider 9 %; a 60 mm tool path trail (40) or a marker (3) it misses.
GOLDEN_TOLERANCE, GOLDEN_ALLOWED_FRACTION = 8, 0.0003


# ------------------------------------------------------------------ PNG without PIL
def png_colours(data, limit=100000):
    """The number of distinct RGBA colours of an 8-bit RGB/RGBA/grey PNG (non-interlaced)."""
    if data[:8] != b'\x89PNG\r\n\x1a\n':
        raise Failure('the screenshot is not a PNG')
    pos, idat, width = 8, [], 0
    while pos < len(data):
        length, kind = struct.unpack('>I4s', data[pos:pos + 8])
        chunk = data[pos + 8:pos + 8 + length]
        if kind == b'IHDR':
            width, height, depth, ctype, _, _, interlace = struct.unpack('>IIBBBBB', chunk)
            if depth != 8 or interlace or ctype not in (0, 2, 4, 6):
                raise Failure('unsupported PNG (depth %d, colour type %d, interlace %d)' % (depth, ctype, interlace))
            bpp = {0: 1, 2: 3, 4: 2, 6: 4}[ctype]
        elif kind == b'IDAT':
            idat.append(chunk)
        elif kind == b'IEND':
            break
        pos += 12 + length
    raw = zlib.decompress(b''.join(idat))
    stride = width * bpp
    prev = bytearray(stride)
    colours = set()
    i = 0
    for _ in range(height):
        ftype = raw[i]
        line = bytearray(raw[i + 1:i + 1 + stride])
        i += 1 + stride
        if ftype == 1:
            for x in range(bpp, stride):
                line[x] = (line[x] + line[x - bpp]) & 255
        elif ftype == 2:
            for x in range(stride):
                line[x] = (line[x] + prev[x]) & 255
        elif ftype == 3:
            for x in range(stride):
                left = line[x - bpp] if x >= bpp else 0
                line[x] = (line[x] + ((left + prev[x]) >> 1)) & 255
        elif ftype == 4:
            for x in range(stride):
                a = line[x - bpp] if x >= bpp else 0
                b = prev[x]
                c = prev[x - bpp] if x >= bpp else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[x] = (line[x] + pred) & 255
        for x in range(0, stride, bpp):
            colours.add(bytes(line[x:x + bpp]))
        if len(colours) >= limit:
            break
        prev = line
    return len(colours), width, height


# ------------------------------------------------------------------ the browser
def start_browser():
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    opts = webdriver.ChromeOptions()
    opts.binary_location = '/usr/bin/chromium'
    for a in ['--headless=new', '--no-sandbox', '--disable-dev-shm-usage', '--window-size=1400,900',
              '--use-angle=swiftshader', '--use-gl=angle', '--enable-unsafe-swiftshader',
              '--ignore-gpu-blocklist', '--hide-scrollbars', '--force-device-scale-factor=1']:
        opts.add_argument(a)
    opts.set_capability('goog:loggingPrefs', {'browser': 'ALL'})
    driver = webdriver.Chrome(service=Service('/usr/bin/chromedriver'), options=opts)
    driver.set_page_load_timeout(30)
    driver.set_script_timeout(10)
    driver.set_window_size(1400, 900)
    # headless=new takes the window's decorations off the viewport: make the page itself 1400x900
    driver.execute_cdp_cmd('Emulation.setDeviceMetricsOverride',
                           {'width': 1400, 'height': 900, 'deviceScaleFactor': 1, 'mobile': False})
    return driver


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--url', required=True)
    ap.add_argument('--screenshot', required=True, help='PNG of the 3D view')
    ap.add_argument('--jog-key')
    ap.add_argument('--jog-axis')
    ap.add_argument('--manual-key', help='a key pressed before jogging (e.g. mMANU)')
    ap.add_argument('--auto-key')
    ap.add_argument('--start-key')
    ap.add_argument('--min-colours', type=int, default=64)
    ap.add_argument('--seek', type=float, help='a replay (vmt view): move the time slider here')
    ap.add_argument('--golden', help="the 3D view's golden PNG at t = 0 (a lockstep run)")
    ap.add_argument('--vmt', help='the vmt binary, whose imgdiff compares with --golden')
    ap.add_argument('--golden-out', help='where the actual and difference pictures go '
                    '(default: golden-view/ beside --screenshot)')
    ap.add_argument('--refresh-golden', action='store_true',
                    help='write the view to --golden instead of comparing')
    args = ap.parse_args()
    if args.golden and not (args.vmt or args.refresh_golden):
        ap.error('--golden needs --vmt (or --refresh-golden)')
    if bool(args.jog_key) != bool(args.jog_axis):
        ap.error('--jog-key and --jog-axis go together')
    if bool(args.auto_key) != bool(args.start_key):
        ap.error('--auto-key and --start-key go together')

    try:
        driver = start_browser()
    except Exception as e:
        print('FAIL: cannot start chromium/chromedriver: %s' % e, file=sys.stderr)
        return 2
    try:
        run_checks(driver, args)
    except Failure as e:
        print('FAIL: %s' % e, file=sys.stderr)
        dump_console(driver)
        return 1
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
    print('ok: all checks passed in %.1f s' % (time.monotonic() - START), flush=True)
    return 0


def dump_console(driver):
    try:
        for entry in driver.get_log('browser')[-20:]:
            print('  console %s: %s' % (entry.get('level'), entry.get('message')), file=sys.stderr)
    except Exception:
        pass


def run_checks(driver, args):
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.action_chains import ActionChains

    def find(css):
        return driver.find_element(By.CSS_SELECTOR, css)

    def text(css):
        return find(css).text.strip()

    def hold(key, seconds):
        """Press a key's button with the mouse, keep it down, release it."""
        b = wait_for('the key %s' % key, lambda: find('[data-key="%s"]' % key), 5)
        ActionChains(driver, duration=10).click_and_hold(b).perform()
        time.sleep(seconds)
        ActionChains(driver, duration=10).release().perform()

    def run_state():
        return text('[data-run-state]')

    try:
        driver.get(args.url)
    except Exception as e:
        first = (getattr(e, 'msg', None) or str(e)).strip().splitlines()
        raise Failure('cannot load %s: %s' % (args.url, first[0] if first else e))
    state = wait_for('[data-nc-state] to have text', lambda: text('[data-nc-state]'), 20)
    ok('page loaded, NC state "%s"' % state)
    keys = driver.find_elements(By.CSS_SELECTOR, '[data-key]')
    if not keys:
        raise Failure('no [data-key] buttons on the page')
    ok('%d machine keys on the panel' % len(keys))
    wait_for('the run state', lambda: run_state() not in ('', '\u2014'), 10)

    if args.golden:
        check_golden(driver, args, run_state, text)

    if args.seek is not None:
        slider = find('[data-seek]')
        if not slider.is_displayed():
            raise Failure('a replay shows no time slider [data-seek]')
        if find('[data-key]').is_enabled():
            raise Failure("a replay's keys are enabled")
        driver.execute_script(
            "arguments[0].value = arguments[1];"
            "arguments[0].dispatchEvent(new Event('change'));", slider, str(args.seek))
        want = '%.3f' % args.seek
        wait_for('the time to go to %s after the slider moved' % want, lambda: text('[data-time]') == want, 20)
        ok('the time slider took the replay to t = %s s' % want)

    if run_state() == 'paused':
        find('[data-run="run"]').click()
        wait_for('the run to be running (it is "%s")' % run_state(), lambda: run_state() == 'running', 10)
        ok('run started')
    else:
        ok('run is "%s"' % run_state())

    if args.jog_key:
        if args.manual_key:
            hold(args.manual_key, 0.3)
            ok('pressed %s' % args.manual_key)
        axis = '[data-axis="%s"]' % args.jog_axis
        before = wait_for('%s to show a position' % axis, lambda: text(axis) if text(axis) not in ('', '\u2014') else None, 10)
        hold(args.jog_key, 1.0)
        after = wait_for('%s to change from %s after holding %s' % (axis, before, args.jog_key),
                         lambda: text(axis) if text(axis) != before else None, 5)
        ok('holding %s moved %s from %s to %s' % (args.jog_key, args.jog_axis, before, after))
        # Judged in simulated time, not the browser's: on a loaded machine the run falls behind
        # the wall clock and catches up. Released, the axis brakes and settles on its position
        # loop; within 3 s of the machine's time it must have been at rest for 0.5 s. Position
        # and time come from one state frame.
        def frame():
            return float(text('[data-time]')), float(text(axis))

        seen = [frame()]
        limit = seen[0][0] + 3.0

        def at_rest():  # (True, frame) at rest, (False, frames) still moving past the limit
            seen.append(frame())
            t = seen[-1][0]
            window = [f for f in seen if f[0] >= t - 0.5]
            if t - window[0][0] >= 0.45 and max(f[1] for f in window) - min(f[1] for f in window) <= 0.01:
                return True, seen[-1]  # 0.01: at rest, not quantisation noise
            return (False, window) if t > limit else None
        rested, what = wait_for('%s to come to rest after %s was released' % (args.jog_axis, args.jog_key), at_rest, 30)
        if not rested:
            raise Failure('%s still moves 3 s after %s was released (%s)' % (args.jog_axis, args.jog_key, ', '.join(
                '%.3f at t = %.3f' % (x, t) for t, x in what[::max(1, len(what) // 6)])))
        ok('%s stopped after the release (%.3f at t = %.3f)' % (args.jog_axis, what[1], what[0]))

    if args.auto_key:
        line = lambda: int(find('[data-current-line]').get_attribute('data-current-line') or 0)
        first = line()
        hold(args.auto_key, 0.3)
        hold(args.start_key, 0.3)
        seen = set()

        def advanced():
            n = line()
            seen.add(n)
            return n if (n > 0 and n != first) or len([s for s in seen if s > 0]) > 1 else None
        n = wait_for('the current line to advance from %d after %s, %s' % (first, args.auto_key, args.start_key), advanced, 10)
        ok('%s, %s: the current line went from %d to %d ("%s")' % (args.auto_key, args.start_key, first, n, text('[data-current-line]')))

    find('[data-run="pause"]').click()
    wait_for('the run to be paused (it is "%s")' % run_state(), lambda: run_state() == 'paused', 10)
    t0 = float(text('[data-time]'))
    time.sleep(0.3)
    t1 = float(text('[data-time]'))
    if t1 != t0:
        raise Failure('the time moves while paused (%.3f, then %.3f)' % (t0, t1))
    ok('paused at t = %.3f s' % t1)
    find('[data-run="step"]').click()
    t2 = wait_for('the time to advance after Step', lambda: float(text('[data-time]')) if float(text('[data-time]')) > t1 else None, 5)
    if t2 - t1 > 0.5:
        raise Failure('one step advanced the time by %.3f s, more than a PLC cycle should' % (t2 - t1))
    ok('step advanced the time by %.3f s (%.3f -> %.3f)' % (t2 - t1, t1, t2))

    canvas = find('canvas[data-view="machine"]')
    time.sleep(0.3)  # a frame after the last state
    png = canvas.screenshot_as_png
    with open(args.screenshot, 'wb') as f:
        f.write(png)
    colours, w, h = png_colours(png)
    if colours < args.min_colours:
        raise Failure('the 3D view has only %d colours (want >= %d): is WebGL rendering? (%s)' % (colours, args.min_colours, args.screenshot))
    ok('3D view %dx%d has %d colours, saved to %s' % (w, h, colours, args.screenshot))

    errors = [e for e in driver.get_log('browser') if e.get('level') == 'SEVERE'
              and 'Failed to load resource' not in e.get('message', '')]
    if errors:
        raise Failure('errors in the browser console: ' + ' | '.join(e['message'] for e in errors[:5]))
    ok('no script errors in the browser console')


def view_picture(driver):
    """The 3D view's pixels as its WebGL canvas holds them (PNG bytes): without the page's
    buttons and legend over it, which are the page's layout, not the view."""
    url = driver.execute_script(
        "return document.querySelector('canvas[data-view=\"machine\"]').toDataURL('image/png');")
    if not url or not url.startswith('data:image/png;base64,'):
        raise Failure('the 3D view gave no picture (%s)' % (url or '')[:40])
    return base64.b64decode(url.split(',', 1)[1])


def check_golden(driver, args, run_state, text):
    """The view at t = 0, paused, in a state that depends on nothing but the scene."""
    if run_state() != 'paused' or text('[data-time]') != '0.000':
        raise Failure('the golden view needs a lockstep run paused at t = 0 (it is "%s" at t = %s)'
                      % (run_state(), text('[data-time]')))
    # The view has the state's poses and the turned stock drawn; then the golden's size and
    # camera, and no trail.
    wait_for('the 3D view to show the first state and the stock', lambda: driver.execute_script("""
        const v = window.vmtStation && window.vmtStation.view;
        return v && v.framed && v.stockVersion !== undefined && !v.stockLoading;"""), 20)
    driver.execute_script("""
        const v = window.vmtStation.view;
        const c = v.container;  // its border is outside the view
        c.style.width = arguments[0] + c.offsetWidth - c.clientWidth + 'px';
        c.style.height = arguments[1] + c.offsetHeight - c.clientHeight + 'px';
        if (v.cameras.length) v.setCamera(v.cameras[0]);
        v.clearTrail();""", GOLDEN_W, GOLDEN_H)
    wait_for('the 3D view drawn at %dx%d' % (GOLDEN_W, GOLDEN_H), lambda: driver.execute_script("""
        const v = window.vmtStation.view, c = v.canvas;
        return c.width === arguments[0] && c.height === arguments[1] && !v.dirty;""",
                                                                  GOLDEN_W, GOLDEN_H), 10)
    # two animation frames later the drawing is on the canvas
    driver.execute_async_script("""
        const done = arguments[arguments.length - 1];
        requestAnimationFrame(() => requestAnimationFrame(() => done(true)));""")
    png = view_picture(driver)
    driver.execute_script("""
        const s = window.vmtStation.view.container.style;
        s.width = s.height = '';""")
    if args.refresh_golden:
        os.makedirs(os.path.dirname(os.path.abspath(args.golden)), exist_ok=True)
        with open(args.golden, 'wb') as f:
            f.write(png)
        ok('wrote the golden %s: look at it before committing it' % args.golden)
        return
    where = args.golden_out or os.path.join(os.path.dirname(os.path.abspath(args.screenshot)),
                                            'golden-view')
    os.makedirs(where, exist_ok=True)
    actual = os.path.join(where, 'actual.png')
    diff = os.path.join(where, 'diff.png')
    with open(actual, 'wb') as f:
        f.write(png)
    if os.path.exists(diff):
        os.remove(diff)
    if not os.path.exists(args.golden):
        raise Failure('no golden %s (write it with --refresh-golden); actual: %s'
                      % (args.golden, actual))
    r = subprocess.run([args.vmt, 'imgdiff', args.golden, actual,
                        '--tolerance', str(GOLDEN_TOLERANCE),
                        '--allowed-fraction', str(GOLDEN_ALLOWED_FRACTION), '--diff', diff],
                       capture_output=True, text=True, timeout=60)
    said = (r.stdout + r.stderr).strip()
    if r.returncode != 0:
        shutil.copyfile(args.golden, os.path.join(where, 'golden.png'))
        raise Failure('the 3D view at t = 0 differs from its golden: %s\n  golden: %s\n'
                      '  actual: %s\n  diff:   %s' % (said, args.golden, actual,
                                                    diff if os.path.exists(diff) else '(none)'))
    ok('the 3D view at t = 0 matches its golden (%s)' % said)


if __name__ == '__main__':
    sys.exit(main())
