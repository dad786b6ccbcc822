#!/usr/bin/env python3
"""A far face is found with no option given. No shared clip was shot from a
distance, so one is made from real clips: each frame scaled down until the
face is about FACE_PX wide and set in the middle of a 640x480 frame, the
edges of the clip's own picture stretched out to fill the rest (no new face
comes with them). That shows the detectors' reach in scale on real faces and
real motion; it does not show a far camera's blur, noise or light.

Each clip runs through hkf-estimator as a user would (no option) and with
--detector short (BlazeFace only, the default before RetinaFace); the faces
the face mesh (the first model) measured per clip are printed, and the default must find the face on >= 95 % of
frames of every clip.
usage: far_face_test.py BUILD_DIR VIDEOS_DIR [FACE_PX]
"""
import os
import re
import subprocess
import sys
import tempfile

import cv2

build, videos = sys.argv[1:3]
face_px = float(sys.argv[3]) if len(sys.argv) > 3 else 60.0
sys.path.insert(0, os.path.join(build, "lcmtypes", "python"))
import lcm  # noqa: E402
from hkf import head_pose_measurement_t  # noqa: E402

estimator = os.path.join(build, "estimator", "hkf-estimator")
# clips and the width of their face in px at full size (the median of hkf-estimator's boxes)
clips = {"s20.mp4": 131.0, "d3.mp4": None, "d10.mp4": None}
work = tempfile.mkdtemp()


def run(src, *extra):
    """hkf-estimator on src; (exit code, output, its measurements)."""
    log = os.path.join(work, "out.lcmlog")
    if os.path.exists(log):
        os.unlink(log)
    # the first model's detection is what is measured: no second model (its inference would only cost time)
    p = subprocess.run([estimator, "--source", src, "--second-model", "none", "--lcm-url", f"file://{log}?mode=w", *extra],
                       capture_output=True, text=True, timeout=900)
    msgs = []
    if os.path.exists(log):
        msgs = [m for m in (head_pose_measurement_t.decode(e.data) for e in lcm.EventLog(log, "r") if e.channel == "HEAD_POSE_RAW")
                if m.model == "mesh_pnp"]  # the first model's: one per frame
    return p.returncode, p.stdout + p.stderr, msgs


def median(values):
    values = sorted(values)
    return values[len(values) // 2] if values else 0.0


def far_video(name, face_width):
    """The clip with its face scaled to face_px, in a 640x480 frame; its path."""
    cap = cv2.VideoCapture(os.path.join(videos, name))
    fps = cap.get(cv2.CAP_PROP_FPS) or 30.0
    out_path = os.path.join(work, "far_" + name)
    out = cv2.VideoWriter(out_path, cv2.VideoWriter_fourcc(*"mp4v"), fps, (640, 480))
    scale = face_px / face_width
    while True:
        ok, frame = cap.read()
        if not ok:
            break
        small = cv2.resize(frame, None, fx=scale, fy=scale, interpolation=cv2.INTER_AREA)
        h, w = small.shape[:2]
        if w > 640 or h > 480:
            raise SystemExit(f"far_face_test: {name} at scale {scale:.2f} does not fit 640x480")
        top, left = (480 - h) // 2, (640 - w) // 2
        out.write(cv2.copyMakeBorder(small, top, 480 - h - top, left, 640 - w - left, cv2.BORDER_REPLICATE))
    out.release()
    return out_path


failed = 0
print(f"| clip (face ~{face_px:.0f} px in 640x480) | frames | default: faces found | --detector short: faces found |")
print("| --- | ---: | ---: | ---: |")
for name, width in clips.items():
    if not os.path.exists(os.path.join(videos, name)):
        print(f"SKIP: no {name} in {videos}")
        sys.exit(77)
    if width is None:  # measure it: the default estimator on the clip as it is (its first 3 s: a median)
        code, out, msgs = run(os.path.join(videos, name), "--max-frames", "90")
        width = median([m.face_box[2] - m.face_box[0] for m in msgs if m.valid])
        if code != 0 or width <= 0:
            print(out)
            raise SystemExit(f"far_face_test: no face measured in {name}")
    path = far_video(name, width)
    found = {}
    for label, extra in (("default", ()), ("short", ("--detector", "short"))):
        code, out, msgs = run(path, *extra)
        if code != 0 or not msgs:
            print(out)
            raise SystemExit(f"far_face_test: hkf-estimator failed on {path} ({label})")
        valid = [m for m in msgs if m.valid]
        found[label] = (len(valid), len(msgs))
        if label == "default":
            widths = median([m.face_box[2] - m.face_box[0] for m in valid])
            searches = re.search(r"(\d+) full-frame face searches", out)
    n = found["default"][1]
    print(f"| {name} (face {widths:.0f} px) | {n} | {found['default'][0]} ({100.0 * found['default'][0] / n:.1f} %) | "
          f"{found['short'][0]} ({100.0 * found['short'][0] / found['short'][1]:.1f} %) |")
    if found["default"][0] < 0.95 * n:
        print(f"FAIL: {name}: the default found the far face on {found['default'][0]} of {n} frames (want >= 95 %)")
        failed += 1
    if searches and int(searches.group(1)) > max(1, 0.05 * n):
        print(f"FAIL: {name}: {searches.group(1)} full-frame searches: the track was lost")
        failed += 1
sys.exit(1 if failed else 0)
