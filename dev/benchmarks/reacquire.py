#!/usr/bin/env python3
"""Re-acquire time: how long after a face comes back into view its first
measurement is published. A 640x480 video at 60 fps is built from real clips:
a face clip (letterboxed) whose face leaves the view GAPS times (for 0.5 to
1.3 s: frames of a real room with nobody in it) and comes back. hkf-estimator
runs it paced as a camera (--realtime); for each return, the time from the
first frame with the face back to the publish of the first measurement with a
face (that frame's capture time, plus the gap to it, plus its processing).

usage: reacquire.py BUILD_DIR FACE_CLIP EMPTY_CLIP [RUNS]   (--detector retina, the default, and short)
"""
import os
import statistics
import subprocess
import sys
import tempfile

import cv2

build, face_clip, empty_clip = sys.argv[1:4]
runs = int(sys.argv[4]) if len(sys.argv) > 4 else 3
detectors = ["retina", "short"]
FPS, GAPS = 60.0, 6
sys.path.insert(0, os.path.join(build, "lcmtypes", "python"))
import lcm  # noqa: E402
from hkf import head_pose_measurement_t  # noqa: E402


def letterboxed(path, limit):
    cap, frames = cv2.VideoCapture(path), []
    while len(frames) < limit:
        ok, f = cap.read()
        if not ok:
            break
        s = min(640 / f.shape[1], 480 / f.shape[0])
        small = cv2.resize(f, None, fx=s, fy=s, interpolation=cv2.INTER_AREA)
        top, left = (480 - small.shape[0]) // 2, (640 - small.shape[1]) // 2
        frames.append(cv2.copyMakeBorder(small, top, 480 - small.shape[0] - top, left, 640 - small.shape[1] - left,
                                         cv2.BORDER_CONSTANT))
    if not frames:
        raise SystemExit(f"reacquire: no frames in {path}")
    return frames


face, empty = letterboxed(face_clip, 600), letterboxed(empty_clip, 200)
work = tempfile.mkdtemp()
video = os.path.join(work, "reacquire.mp4")
out = cv2.VideoWriter(video, cv2.VideoWriter_fourcc(*"mp4v"), FPS, (640, 480))
returns, n, k = [], 0, 0
for g in range(GAPS):
    for _ in range(60):  # 1 s with the face
        out.write(face[k % len(face)])
        k, n = k + 1, n + 1
    gap = int(FPS * (0.5 + 0.8 * g / max(1, GAPS - 1))) + g  # 0.5-1.3 s, a different phase each time
    for i in range(gap):
        out.write(empty[i % len(empty)])
        n += 1
    returns.append(n)
for _ in range(60):
    out.write(face[k % len(face)])
    k, n = k + 1, n + 1
out.release()

print(f"Re-acquire on a {n}-frame 640x480 video at {FPS:.0f} fps (--realtime), {GAPS} returns of the face, "
      f"{runs} runs each, side by side:\n")
print("| --detector | re-acquire ms: median | p90 | max | frames dropped (run median) |")
print("| --- | ---: | ---: | ---: | ---: |")
for detector in detectors:
    times, dropped = [], []
    for _ in range(runs):
        log = os.path.join(work, "out.lcmlog")
        if os.path.exists(log):
            os.unlink(log)
        p = subprocess.run([os.path.join(build, "estimator", "hkf-estimator"), "--source", video, "--realtime",
                            "--detector", detector, "--lcm-url", f"file://{log}?mode=w"],
                           capture_output=True, text=True, timeout=600)
        if p.returncode != 0:
            print(p.stdout + p.stderr)
            raise SystemExit(f"reacquire: hkf-estimator --detector {detector} failed")
        dropped.append(int(p.stdout.split(" dropped")[0].rsplit(" ", 1)[-1]))
        msgs = [head_pose_measurement_t.decode(e.data) for e in lcm.EventLog(log, "r") if e.channel == "HEAD_POSE_RAW"]
        start = msgs[0].utime  # frame 0: always taken
        for r in returns:
            back = start + 1e6 * r / FPS  # when the first frame with the face back was captured
            first = next((m for m in msgs if m.valid and m.utime >= back - 1e6 / (2 * FPS)), None)
            if first is None:
                raise SystemExit(f"reacquire: the face never came back after frame {r} (--detector {detector})")
            times.append((first.utime - back + first.inference_us) / 1000.0)
    times.sort()
    print(f"| {detector} | {statistics.median(times):.0f} | {times[int(0.9 * (len(times) - 1))]:.0f} | {times[-1]:.0f} | "
          f"{statistics.median(dropped):.0f} |")
