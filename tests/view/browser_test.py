#!/usr/bin/env python3
"""The live view in a real browser: Debian's Chromium, headless, driven over its DevTools protocol while a
tracker plays a clip as the camera (view_browser_test.sh). Checked, as a player would see it:
- the camera picture with the face's box (yellow) and the head's axes, and the traces (filtered and raw);
- the page's status line is hkf-track's line (TRACK.txt);
- the rest's countdown appears, and ends measured;
- the Recentre button makes the node recentre (its command count, the centre);
- the stillness knob changes the wander in use (HEAD_POSE_STATUS, as the page shows it).
A screenshot goes to OUT.png. usage: browser_test.py CHROMIUM BASE_URL TRACK.txt OUT.png"""
import os
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "dev", "view"))
from chromium_page import Page  # noqa: E402


# Pixels of the picture as drawn on the page: the face box's yellow and the axes' red, green and blue lines.
PICTURE_COLOURS = """(() => {
  const img = document.getElementById('camera'), c = document.createElement('canvas');
  c.width = img.naturalWidth; c.height = img.naturalHeight;
  const g = c.getContext('2d'); g.drawImage(img, 0, 0);
  const d = g.getImageData(0, 0, c.width, c.height).data;
  let yellow = 0, red = 0, green = 0, blue = 0;
  for (let i = 0; i < d.length; i += 4) {
    const [r, gr, b] = [d[i], d[i + 1], d[i + 2]];
    if (r > 200 && gr > 200 && b < 90) yellow++;
    else if (r > 200 && gr < 80 && b < 80) red++;
    else if (gr > 170 && r < 100 && b < 100) green++;
    else if (b > 200 && r < 80 && gr < 120) blue++;
  }
  return {width: c.width, yellow, red, green, blue};
})()"""
# Pixels of the traces: the filtered one white, the raw mesh's light blue.
TRACE_COLOURS = """(() => {
  const c = document.getElementById('traces'), d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
  let white = 0, raw = 0;
  for (let i = 0; i < d.length; i += 4) {
    if (d[i] > 240 && d[i + 1] > 240 && d[i + 2] > 240) white++;
    if (d[i] < 120 && d[i + 1] > 170 && d[i + 2] > 220) raw++;
  }
  return {white, raw};
})()"""


def check_rest_and_line(page, track_path):
    """The countdown seen and then measured; the page's line one of hkf-track's."""
    seen, until = set(), time.time() + 40
    while time.time() < until and not ({"countdown", "measured"} <= seen):
        text = page.js("document.getElementById('rest-text').textContent")
        seen |= {"countdown"} if "keep still:" in text else {"measured"} if text == "Rest measured." else set()
        time.sleep(0.1)
    if not {"countdown", "measured"} <= seen:
        raise SystemExit(f"browser_test: the rest's countdown and its end were not both shown ({seen})")
    line = page.js("document.getElementById('line').textContent")
    with open(track_path) as f:
        if line not in (l.rstrip("\n") for l in f):
            raise SystemExit(f"browser_test: the page's line is not hkf-track's: {line!r}")
    print(f"browser_test: the rest counted down and was measured; the page's line is hkf-track's: {line[:60]}...")


def check_recentre(page):
    """Recentre: hkf-filter counts the command (and asks for a new rest, which check_rest_and_line then watches)."""
    page.wait_for("window.latestStatus !== undefined", "hkf-filter's status", 30)
    before = page.js("window.latestStatus.commands")
    page.js("document.getElementById('recenter').click()")
    page.wait_for(f"window.latestStatus.commands === {before + 1}", "recentre counted by hkf-filter", 30)
    print(f"browser_test: recentre took (hkf-filter's commands {before} -> {before + 1})")


def check_knob(page):
    """The knob at 2.5: the stillness in hkf-filter's status, and the wander in use 2.5 x the rest's own."""
    page.js("const k = document.getElementById('stillness'); k.value = 2.5; k.dispatchEvent(new Event('input'));"
            "k.dispatchEvent(new Event('change'))")
    page.wait_for("window.latestStatus.stillness === 2.5", "stillness 2.5 in hkf-filter's status", 30)
    status = page.wait_for("window.latestStatus.wander_measured && window.latestStatus", "a measured rest", 30)
    measured = min(max(s - n for s, n in zip(status["rest_spread"], status["rest_noise"])), 0.3)
    if abs(status["wander"] - 2.5 * measured) > 1e-3:
        raise SystemExit(f"browser_test: the wander in use {status['wander']} is not 2.5 x {measured:.4f}")
    shown = page.js("document.getElementById('wander-text').textContent")
    if "stillness 2.50" not in shown or f"the rest's {measured:.3f}" not in shown:
        raise SystemExit(f"browser_test: the page does not show the knob's stillness: {shown!r}")
    print(f"browser_test: stillness 2.5: wander {status['wander']:.3f} = 2.5 x {measured:.3f} deg^2")


def main():
    chromium, base, track_path, out_png = sys.argv[1:5]
    with tempfile.TemporaryDirectory() as profile:
        page = Page(chromium, profile)
        try:
            page.call("Page.navigate", url=base + "/")
            page.wait_for("document.getElementById('connection').textContent === 'live'", "live connection", 30)
            check_recentre(page)  # first: the rest it asks for is then watched from its start
            check_rest_and_line(page, track_path)
            check_knob(page)
            picture = page.wait_for(f"document.getElementById('camera').naturalWidth > 0 && {PICTURE_COLOURS}",
                                    "camera picture", 10)
            traces = page.js(TRACE_COLOURS)
            print(f"browser_test: picture {picture}; traces {traces}")
            if picture["width"] != 320 or picture["yellow"] < 100 or min(picture["red"], picture["blue"]) < 15:
                raise SystemExit("browser_test: the picture lacks the face's box or the head's axes")
            if traces["white"] < 500 or traces["raw"] < 300:
                raise SystemExit("browser_test: the traces are not drawn")
            print(f"browser_test: screenshot {out_png} ({page.screenshot(out_png)} bytes); ok")
        finally:
            page.close()


if __name__ == "__main__":
    main()
