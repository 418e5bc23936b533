#!/usr/bin/env python3
"""Opens a report.html in headless Chromium and checks what a user would see.

Usage: check_report_in_browser.py REPORT_HTML SCREENSHOT_PNG [--displacement]

1. Chromium renders the page (software WebGL, SwiftShader); the page's status element (#report-status)
   says where its WebGL canvas and chart boxes are, which tissues it drew and any script error.
2. A second run takes a screenshot (kept as SCREENSHOT_PNG, a test artefact).
3. In the screenshot, the canvas must hold pixels of every tissue's colour (lit surfaces keep a
   colour's chromaticity, so pixels are matched by direction in RGB space, not by value), every chart
   box must be drawn on, and Chromium's console must have no error.
With --displacement the page opens in its displacement view (#displacement): the canvas must then
show the viridis colours of |u| instead.
Exit 0 when all holds; otherwise every failure is printed and the exit code is 1.
"""
import html
import json
import math
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile

from PIL import Image

WIDTH, HEIGHT = 1400, 2600
VIRIDIS = [(0.267, 0.005, 0.329), (0.254, 0.265, 0.530), (0.164, 0.471, 0.558), (0.135, 0.659, 0.518),
           (0.478, 0.821, 0.318), (0.993, 0.906, 0.144)]


def chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    print("chromium not found (Debian package chromium; scripts/setup.sh installs it)")
    sys.exit(77)


def run_chromium(args, url, profile, attempts=2, timeout=150):
    """Runs headless Chromium on url; returns its CompletedProcess. Headless Chromium can hang for
    good on a loaded machine (seen with --screenshot and a virtual time budget: minutes with no
    output, where the same page takes seconds): such a run is killed with its process group and
    run again, `attempts` times in all, each in a fresh profile; a page that never finishes then
    fails the test."""
    cmd = [chromium(), "--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--hide-scrollbars",
           "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist",
           "--no-first-run", "--disable-extensions", "--enable-logging=stderr", "--v=0",
           f"--window-size={WIDTH},{HEIGHT}",
           "--virtual-time-budget=20000", "--run-all-compositor-stages-before-draw"] + args + [url]
    for attempt in range(1, attempts + 1):
        run_profile = os.path.join(profile, f"attempt{attempt}")
        proc = subprocess.Popen(cmd[:1] + [f"--user-data-dir={run_profile}"] + cmd[1:], stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True, start_new_session=True)
        try:
            out, err = proc.communicate(timeout=timeout)
            return subprocess.CompletedProcess(proc.args, proc.returncode, out, err)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.communicate()
            print(f"chromium {' '.join(args)}: no result after {timeout} s (attempt {attempt} of {attempts}), killed")
    print(f"chromium never finished the page in {attempts} attempts")
    sys.exit(1)


def unit(rgb):
    n = math.sqrt(sum(c * c for c in rgb))
    return tuple(c / n for c in rgb) if n > 0 else (0.0, 0.0, 0.0)


def angle(a, b):
    return math.degrees(math.acos(max(-1.0, min(1.0, sum(x * y for x, y in zip(a, b))))))


def hex_rgb(h):
    return tuple(int(h[i:i + 2], 16) / 255.0 for i in (1, 3, 5))


def count_matches(image, box, colours, max_angle):
    """Pixels in box (x, y, w, h) whose colour direction is nearest to each of colours (within max_angle deg)."""
    x0, y0, w, h = (int(round(v)) for v in box)
    crop = image.crop((x0, y0, x0 + w, y0 + h)).convert("RGB")
    targets = [unit(c) for c in colours]
    counts = [0] * len(colours)
    for r, g, b in crop.getdata():
        if max(r, g, b) < 40:
            continue  # too dark to tell a colour
        u = unit((r, g, b))
        best, best_angle = None, max_angle
        for i, t in enumerate(targets):
            a = angle(u, t)
            if a < best_angle:
                best, best_angle = i, a
        if best is not None:
            counts[best] += 1
    return counts


def drawn_pixels(image, box, background=(255, 255, 255)):
    x0, y0, w, h = (int(round(v)) for v in box)
    crop = image.crop((x0, y0, x0 + w, y0 + h)).convert("RGB")
    return sum(1 for p in crop.getdata() if max(abs(p[i] - background[i]) for i in range(3)) > 30)


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    page, shot = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    displacement = "--displacement" in sys.argv[3:]
    url = "file://" + page + ("#displacement" if displacement else "")
    failures = []
    with tempfile.TemporaryDirectory() as profile:
        dom = run_chromium(["--dump-dom"], url, profile)
    m = re.search(r'<pre id="report-status"[^>]*>(.*?)</pre>', dom.stdout, re.S)
    if not m or not m.group(1).strip():
        print("the page did not write its status (script did not run?)\n" + dom.stderr[-3000:])
        return 1
    status = json.loads(html.unescape(m.group(1)))
    console_errors = [l for l in dom.stderr.splitlines() if "CONSOLE" in l and ("ERROR" in l or "Uncaught" in l)]
    if status["errors"]:
        failures.append("page errors: " + "; ".join(status["errors"]))
    if console_errors:
        failures.append("console errors:\n  " + "\n  ".join(console_errors))
    if not status.get("scene"):
        failures.append("no 3D view drawn")
    if status.get("first_frame_ms") is None:
        failures.append("the page never drew its first frame")
    with tempfile.TemporaryDirectory() as profile:
        run_chromium([f"--screenshot={shot}"], url, profile)
    if not os.path.exists(shot):
        failures.append("no screenshot written")
        print("\n".join(failures))
        return 1
    image = Image.open(shot)
    canvas = status["canvas"]
    box = (canvas["x"], canvas["y"], canvas["w"], canvas["h"])
    if displacement:
        counts = count_matches(image, box, VIRIDIS, 6.0)
        print(f"displacement view: {sum(counts)} pixels in viridis colours")
        if sum(counts) < 2000:
            failures.append(f"the displacement view shows {sum(counts)} viridis pixels (expected >= 2000)")
    else:
        tissues = status["tissue_colors"]
        counts = count_matches(image, box, [hex_rgb(t["color"]) for t in tissues], 4.0)
        for t, n in zip(tissues, counts):
            print(f"tissue {t['name']:>10} {t['color']}: {n} pixels in the 3D view")
            if n < 150:
                failures.append(f"tissue {t['name']} ({t['color']}) has {n} pixels in the 3D view (expected >= 150)")
    for c in status["chart_boxes"]:
        if c["y"] + c["h"] > image.size[1]:
            continue  # below the screenshot
        n = drawn_pixels(image, (c["x"], c["y"], c["w"], c["h"]))
        print(f"chart {c['id']:>24}: {n} drawn pixels")
        if n < 1500:
            failures.append(f"chart {c['id']} looks empty ({n} drawn pixels)")
    if status["charts"] < 1:
        failures.append("no chart rendered")
    print(f"first frame after {status.get('first_frame_ms')} ms; {status['charts']} charts; screenshot {shot}")
    if failures:
        print("FAILED:\n" + "\n".join(failures))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
