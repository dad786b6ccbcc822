#!/usr/bin/env python3
"""The live view as a player sees it, a few seconds into a run: opens BASE_URL in headless Chromium, waits
until the camera picture and the traces are in, then SECONDS more, and saves a screenshot.
usage: screenshot.py BASE_URL OUT.png [SECONDS]"""
import os
import shutil
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from chromium_page import Page  # noqa: E402


def main():
    base, out = sys.argv[1], sys.argv[2]
    seconds = float(sys.argv[3]) if len(sys.argv) > 3 else 6.0
    chromium = shutil.which("chromium")
    if chromium is None:
        sys.exit("screenshot: no chromium (scripts/setup.sh installs it)")
    with tempfile.TemporaryDirectory() as profile:
        page = Page(chromium, profile)
        try:
            page.call("Page.navigate", url=base + "/")
            page.wait_for("document.getElementById('camera').naturalWidth > 0", "camera picture", 30)
            time.sleep(seconds)
            print(f"screenshot: {out} ({page.screenshot(out)} bytes)")
        finally:
            page.close()


if __name__ == "__main__":
    main()
