#!/usr/bin/env python3
"""Big turns end to end: does the second model keep up with the camera beyond the mesh's reach?

Truth clips cannot turn a head beyond the image plane, so the turned heads are real ones:
FACES faces of the AFLW2000 development split at |yaw| >= 60 deg (all three labelled angles
within +-99 deg, spread evenly over the sorted list), each held HOLD_S seconds in a 640x480
frame with fresh sensor noise and JPEG on every frame. The clip is played as a camera
(`--realtime`) at 30 and 60 fps through the real programs, as e2e.py plays its truth clips:

    hkf-estimator (default pipeline) -> hkf-filter (live) -> hkf-opentrack -> a UDP receiver

Every frame of the clip has |yaw| >= 60 deg, so every figure is "while the head is turned":
  WHENet /s         WHENet's measurements per second of clip
  measured          frames with a measurement (either model) whose yaw is within 20 deg of
                    the label, as a share of the frames captured (goal: >= 95 % at 30 and
                    60 fps)
  capture->publish  WHENet's measurements: the frame's capture to lcm-logger's arrival stamp,
                    p50 / p99 (goal at 30 fps: <= 25 / 40 ms)
  capture->datagram WHENet's measurements: the frame's capture to the first datagram of the first
                    pose the node published after the measurement reached it
  dropped           frames the estimator dropped (its own count)
  mesh not run      frames left to WHENet alone (--second-alone-from-yaw: its newest answer at a big turn)
and, for the defaults, where WHENet's capture->publish goes (the estimator's summary: until it was asked, waiting
for the worker, its inference).

--simd LEVEL plays a CPU of that level (avx2, avx, sse2): hkf's layers forced to it (HKF_SIMD) and OpenCV's own
held to it (OPENCV_CPU_DISABLE, dev/benchmarks/opencv_cpu_levels.txt), so an AVX-512 machine measures what
an AVX2 one gives.

usage: big_turns.py [--build DIR] [--out DIR] [--faces N] [--simd LEVEL]
Needs root (a private network namespace: nothing leaves the machine); exit 77 otherwise.
"""
import argparse
import csv
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import e2e  # noqa: E402
import evaluate  # noqa: E402
import truth_clips  # noqa: E402

ROOT = e2e.ROOT
AFLW = os.path.join(ROOT, "..", "shared", "data", "aflw2000")
FACES, HOLD_S, MIN_YAW, YAW_WITHIN = 12, 1.0, 60.0, 20.0
FRAME_W, FRAME_H = 640, 480
RATES = [30.0, 60.0]
VARIANTS = [e2e.Variant("defaults"),  # the mesh, WHENet beside it where the mesh's |yaw| >= 10 deg or no pose
            e2e.Variant("--second-alone-from-yaw 0 (the mesh on every frame)",
                        estimator_options=["--second-alone-from-yaw", "0"]),
            e2e.Variant("--second-model none (the mesh alone)", estimator_options=["--second-model", "none"])]
GOALS = {30.0: (0.95, 25.0, 40.0), 60.0: (0.95, None, None)}  # measured share, capture->publish p50, p99


def turned_faces(count):
    """(image path, label pitch, yaw, roll in hkf's convention) of `count` faces at |yaw| >= MIN_YAW."""
    with open(os.path.join(AFLW, "labels.csv")) as f:
        rows = [r for r in csv.DictReader(f)
                if all(abs(float(r[k])) <= 99.0 for k in ("yaw_deg", "pitch_deg", "roll_deg"))
                and abs(float(r["yaw_deg"])) >= MIN_YAW]
    rows.sort(key=lambda r: r["image"])
    if len(rows) < count:
        evaluate.fail(f"{AFLW}: only {len(rows)} faces at |yaw| >= {MIN_YAW:g} deg")
    picked = [rows[int(i)] for i in np.linspace(0, len(rows) - 1, count).round()]
    # AFLW2000's labels: pitch up and yaw as hkf's; roll the other way (dataset_eval.cpp)
    return [(os.path.join(AFLW, "images", r["image"]),
             (float(r["pitch_deg"]), float(r["yaw_deg"]), -float(r["roll_deg"]))) for r in picked]


def framed(path):
    """An AFLW image scaled to the frame's height, in the middle of a 640x480 frame."""
    import cv2
    image = cv2.imread(path)
    if image is None:
        evaluate.fail(f"cannot read {path}")
    s = FRAME_H / image.shape[0]
    image = cv2.resize(image, (int(round(image.shape[1] * s)), FRAME_H), interpolation=cv2.INTER_AREA)
    left = (FRAME_W - image.shape[1]) // 2
    return cv2.copyMakeBorder(image, 0, 0, left, FRAME_W - image.shape[1] - left, cv2.BORDER_REFLECT_101)


class TurnClip:
    def __init__(self, name, folder, fps, truth):
        self.name, self.folder, self.fps, self.truth = name, folder, fps, truth  # truth: per frame (pitch, yaw, roll)


def make_clip(out, faces, fps):
    label = f"aflw_turned_{len(faces)}x{HOLD_S:g}s_{fps:g}fps"
    folder = os.path.join(out, "clips", label)
    per_face = int(round(HOLD_S * fps))
    truth = np.repeat(np.array([angles for _, angles in faces]), per_face, axis=0)
    if not os.path.exists(os.path.join(folder, f"{len(truth) - 1:05d}.jpg")):
        os.makedirs(folder, exist_ok=True)
        rng = np.random.default_rng(len(faces) * 1000 + int(fps))
        for k, (path, _) in enumerate(faces):
            frame = framed(path)
            centre = (FRAME_W / 2.0, FRAME_H / 2.0)
            for i in range(per_face):
                image = truth_clips.render(frame, centre, 0.0, rng=rng)
                truth_clips.write_jpeg(os.path.join(folder, f"{k * per_face + i:05d}.jpg"), image)
        e2e.log(f"{label}: {len(truth)} frames written")
    return TurnClip(label, folder, fps, truth)


def read_log(path, types_dir):
    """Every raw measurement (arrival us, capture us, seq, valid, yaw, model) and measured pose (arrival, measurement_utime)."""
    raw, poses = [], []
    for timestamp, channel, m in e2e.decoded_events(path, types_dir):
        if channel == "HEAD_POSE_RAW":
            raw.append((timestamp, m.utime, m.seq, m.valid, m.yaw, m.model))
        elif not m.extrapolated:
            poses.append((timestamp, m.measurement_utime))
    return raw, poses


def percentile(values, q):
    return float(np.percentile(values, q)) if len(values) else float("nan")


def measure(clip, datagrams, raw, poses, summary):
    frames = len(clip.truth)
    first_seq = min(r[2] for r in raw) if raw else 0
    good = set()
    for _, _, seq, valid, yaw, _ in raw:
        k = seq - first_seq
        if valid and 0 <= k < frames and abs(yaw - clip.truth[k][1]) <= YAW_WITHIN:
            good.add(k)
    whenet = [r for r in raw if r[5] == "whenet" and r[3]]
    publish = [(r[0] - r[1]) / 1000.0 for r in whenet]
    arrivals = np.array(sorted(t for t, _ in datagrams), float)
    pose_times = np.array(sorted(t for t, _ in poses), float)
    to_datagram = []
    for t_raw, capture, *_ in whenet:  # the first pose the node published after it took the measurement, and
        k = np.searchsorted(pose_times, t_raw)  # the first datagram after that pose
        after = np.searchsorted(arrivals, pose_times[k]) if k < len(pose_times) else len(arrivals)
        if after < len(arrivals):
            to_datagram.append((arrivals[after] - capture) / 1000.0)
    return {"whenet_per_s": len(whenet) / (frames / clip.fps), "measured": len(good) / frames,
            "publish": (percentile(publish, 50), percentile(publish, 99)),
            "datagram": (percentile(to_datagram, 50), percentile(to_datagram, 99)),
            "dropped": e2e.parse_dropped(summary), "frames": frames, "set_aside": set_aside_frames(summary)}


def set_aside_frames(summary):
    """The frames the estimator did not run the mesh on (--second-alone-from-yaw), as text ("-": not counted)."""
    found = re.search(r"not run on (\d+) frames", summary)
    return found.group(1) if found else "-"


def verdict(fps, m):
    share, p50, p99 = GOALS[fps]
    parts = [f"measured >= {share:.0%}: {'met' if m['measured'] >= share else 'NOT met'}"]
    if p50 is not None:
        ok = m["publish"][0] <= p50 and m["publish"][1] <= p99
        parts.append(f"capture->publish <= {p50:g} / {p99:g} ms: {'met' if ok else 'NOT met'}")
    return "; ".join(parts)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(ROOT, "out", "e2e"))
    parser.add_argument("--faces", type=int, default=FACES)
    parser.add_argument("--simd", help="the instruction-set level to play (avx512, avx2, avx, sse2); default: this CPU's")
    args = parser.parse_args()
    if args.simd:
        levels = dict((line.split() + [""])[:2] for line in open(os.path.join(ROOT, "dev", "benchmarks", "opencv_cpu_levels.txt"))
                      if line.strip() and not line.startswith("#"))
        if args.simd not in levels:
            evaluate.fail(f"--simd is one of {', '.join(levels)}, not '{args.simd}'")
        os.environ["HKF_SIMD"], os.environ["OPENCV_CPU_DISABLE"] = args.simd, levels[args.simd]
    if os.environ.get("HKF_IN_NETNS") != "1":
        os.environ["HKF_IN_NETNS"] = "1"
        netns = os.path.join(ROOT, "tools", "lcm-netns")
        os.execv(netns, [netns, sys.executable, os.path.abspath(__file__)] + sys.argv[1:])
    if args.faces < 1:
        evaluate.fail("--faces must be at least 1")
    build, out = os.path.abspath(args.build), os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    faces = turned_faces(args.faces)
    lines = [f"Big turns: {len(faces)} AFLW2000 dev-split faces at |yaw| >= {MIN_YAW:g} deg, each held "
             f"{HOLD_S:g} s, played as a camera through the live chain (big_turns.py); hkf's layers at "
             f"{os.environ.get('HKF_SIMD') or 'the best this CPU runs'}; on {evaluate.cpu_named()}.\n",
             "| estimator | fps | frames | dropped | WHENet /s | measured (yaw within 20 deg) | capture->publish p50 / p99 "
             "| capture->datagram p50 / p99 | mesh not run |", "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    verdicts, breakdown = [], []
    for fps in RATES:
        clip = make_clip(out, faces, fps)
        for variant in VARIANTS:
            datagrams, log_path, summary = e2e.run_chain(build, clip, variant, os.path.join(out, "work", clip.name))
            raw, poses = read_log(log_path, os.path.join(build, "lcmtypes", "python"))
            if not raw:
                evaluate.fail(f"{clip.name}: no raw measurement logged")
            m = measure(clip, datagrams, raw, poses, summary)
            lines.append(f"| {variant.name} | {fps:g} | {m['frames']} | {m['dropped']} | {m['whenet_per_s']:.1f} | "
                         f"{m['measured']:.0%} | {m['publish'][0]:.0f} / {m['publish'][1]:.0f} ms | "
                         f"{m['datagram'][0]:.0f} / {m['datagram'][1]:.0f} ms | {m['set_aside']} |")
            if variant is VARIANTS[0]:
                verdicts.append(f"- the defaults at {fps:g} fps: {verdict(fps, m)}.")
                where = [line.split("(p50 / p99 ms): ", 1)[-1] for line in summary.splitlines()
                         if "where it goes" in line]
                breakdown.append(f"- {fps:g} fps (p50 / p99 ms): {where[0]}" if where else
                                 f"- {fps:g} fps: the estimator gave no account of WHENet's time")
            e2e.log(lines[-1])
    text = "\n".join(lines + [""] + verdicts + ["", "Where WHENet's capture->publish goes (the defaults):"] +
                     breakdown) + "\n"
    with open(os.path.join(out, "big_turns.md"), "w") as f:
        f.write(text)
    print(text, end="")
    return 0


if __name__ == "__main__":
    sys.exit(main())
