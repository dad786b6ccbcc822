#!/usr/bin/env python3
"""What the live view costs the tracker: hkf-track plays the same clip as a camera, without the view, with
the view and a viewer that reads it as the page does (the event stream and every picture), and with the view
while 100 viewers connect and drop; runs alternate, ROUNDS of each. Per run, from the filtered poses logged
(lcm-logger on HEAD_POSE): the capture->pose latency p50 and the pose rate. Run it inside a private network
namespace: tools/lcm-netns .venv/bin/python dev/benchmarks/view_cost.py build [VIDEO] [ROUNDS]"""
import os
import statistics
import subprocess
import sys
import tempfile
import threading
import time
import urllib.request

import lcm

BUILD = sys.argv[1] if len(sys.argv) > 1 else "build"
VIDEO = sys.argv[2] if len(sys.argv) > 2 else "../shared/data/videos/d14.mp4"
ROUNDS = int(sys.argv[3]) if len(sys.argv) > 3 else 3
sys.path.insert(0, os.path.join(BUILD, "lcmtypes", "python"))
from hkf import head_pose_t  # noqa: E402
PORT = 7691
BASE = f"http://127.0.0.1:{PORT}"


def wait_for_view(seconds=60):
    until = time.time() + seconds
    while time.time() < until:
        try:
            urllib.request.urlopen(BASE + "/view.css", timeout=1).read()
            return
        except OSError:
            time.sleep(0.1)
    sys.exit("view_cost: the view did not open")


def one_viewer(stop):
    """The page's reads: the event stream, and each picture it announces."""
    with urllib.request.urlopen(BASE + "/events", timeout=5) as stream:
        while not stop.is_set():
            line = stream.readline()
            if not line:
                return
            if line.startswith(b'data: {"t":"picture"'):
                urllib.request.urlopen(BASE + "/picture.jpg", timeout=5).read()


def dropping_viewers(stop, count=100):
    """count viewers, one after another, each connecting, reading a little and dropping."""
    for _ in range(count):
        if stop.is_set():
            return
        try:
            with urllib.request.urlopen(BASE + "/events", timeout=2) as stream:
                stream.read(64)
        except OSError:
            pass
        time.sleep(0.05)


def run(mode, work):
    log = os.path.join(work, f"{mode}.lcmlog")
    logger = subprocess.Popen(["lcm-logger", "-q", "-f", "-c", "HEAD_POSE", log])
    time.sleep(0.5)
    command = [os.path.join(BUILD, "tools", "hkf-track"), "--source", VIDEO, "--realtime", "--logs",
               os.path.join(work, mode + "-logs")] + (["--view", str(PORT)] if mode != "without" else [])
    track = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    stop = threading.Event()
    if mode != "without":
        wait_for_view()
        threading.Thread(target=one_viewer if mode == "one viewer" else dropping_viewers, args=(stop,), daemon=True).start()
    if track.wait(timeout=300) != 0:
        sys.exit(f"view_cost: hkf-track failed ({mode})")
    stop.set()
    time.sleep(0.3)
    logger.terminate()
    logger.wait()
    poses = [head_pose_t.decode(e.data) for e in lcm.EventLog(log, "r") if e.channel == "HEAD_POSE"]
    poses = [p for p in poses if not p.extrapolated and p.latency_us > 0]
    span = (poses[-1].utime - poses[0].utime) / 1e6
    return statistics.median(p.latency_us / 1000 for p in poses), (len(poses) - 1) / span


def main():
    results = {m: [] for m in ("without", "one viewer", "100 dropping")}
    with tempfile.TemporaryDirectory() as work:
        for r in range(ROUNDS):
            for mode in results:
                results[mode].append(run(mode, work))
                print(f"view_cost: round {r + 1}/{ROUNDS}, {mode}: capture->pose p50 {results[mode][-1][0]:.2f} ms, "
                      f"{results[mode][-1][1]:.2f} poses/s", flush=True)
    base = statistics.median(p50 for p50, _ in results["without"])
    print(f"\nhkf-track on {os.path.basename(VIDEO)} as a camera, {ROUNDS} runs of each, alternating:\n")
    print("| the view | capture->pose p50 (median of runs) | vs without | poses/s (median) |")
    print("| --- | ---: | ---: | ---: |")
    for mode, runs in results.items():
        p50 = statistics.median(x for x, _ in runs)
        print(f"| {mode} | {p50:.2f} ms ({', '.join(f'{x:.2f}' for x, _ in runs)}) | {p50 - base:+.2f} ms | "
              f"{statistics.median(y for _, y in runs):.2f} |")


if __name__ == "__main__":
    main()
