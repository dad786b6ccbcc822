#!/usr/bin/env python3
"""An independent truth check: the filter's defaults against the 1 euro filter on a face and on
trajectories the project does not have, and on which nothing was tuned.

The face: scikit-image's `astronaut.png` (NASA's portrait of Eileen Collins, public domain), read out of
the scikit-image wheel that pip downloads from PyPI at run time (nothing is committed). The project's
truth clips (truth_eval.py) turn frames of the team's own videos.

The trajectories: made here, not by truth_motion.py (whose minimum-jerk glances, drifts, sines and
tremor the defaults were chosen on): holds of 1-3 s between moves of 5-50 deg to a target within
+-50 deg, each a raised-cosine turn (theta = a + (b - a)(1 - cos(pi s)) / 2) of 0.2-1.0 s, and now and
then a slow pan of 5-15 deg at 5-15 deg/s. Seeded: the same clips every run.

The construction is truth_eval.py's (truth_clips.py: the image turned in its plane about the face
centre, fresh sensor noise and JPEG on every frame; hkf-estimator's default model at 30 fps), and so
are the metrics and the comparison: every setting of evaluate.py's sweep, the defaults as shipped
against each filter's best setting at no more still jitter.

usage: independent_truth.py [--build DIR] [--out DIR] [--clips N] [--seconds S]
writes OUT/independent/{independent.md,independent_roll.png} and the clips under OUT/independent/clips.
"""
import argparse
import glob
import os
import subprocess
import sys
import time
import zipfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import evaluate  # noqa: E402
import truth_clips  # noqa: E402
import truth_eval  # noqa: E402
import truth_motion  # noqa: E402

FACE_PACKAGE = "scikit-image==0.26.0"
FACE_MEMBER = "skimage/data/astronaut.png"
FPS = truth_eval.FPS


def log(message):
    print(f"independent_truth: {message}", flush=True)


def fetch_face(folder):
    """The astronaut's portrait as a BGR image, from the scikit-image wheel on PyPI (downloaded once)."""
    import cv2
    os.makedirs(folder, exist_ok=True)
    wheels = glob.glob(os.path.join(folder, "scikit_image-*.whl"))
    if not wheels:
        pip = os.path.join(os.path.dirname(sys.executable), "pip")
        result = subprocess.run([pip, "download", "--no-deps", "--only-binary", ":all:", "-d", folder, FACE_PACKAGE],
                                capture_output=True, text=True)
        wheels = glob.glob(os.path.join(folder, "scikit_image-*.whl"))
        if result.returncode != 0 or not wheels:
            evaluate.fail(f"pip download {FACE_PACKAGE} failed: {result.stderr.strip()[-300:]}")
    with zipfile.ZipFile(wheels[0]) as wheel:
        data = np.frombuffer(wheel.read(FACE_MEMBER), dtype=np.uint8)
    image = cv2.imdecode(data, cv2.IMREAD_COLOR)
    if image is None:
        evaluate.fail(f"{FACE_MEMBER} in {wheels[0]} is not an image")
    return image


def face_centre(build, image, work):
    """The face's centre (px) as the estimator finds it on the unturned image: the median over a few frames."""
    folder = os.path.join(work, "unturned")
    log_path = os.path.join(work, "unturned.lcmlog")
    if not os.path.exists(log_path):
        truth_clips.write_still_clip(folder, image, (image.shape[1] / 2.0, image.shape[0] / 2.0), np.zeros(15), 1)
        truth_eval.estimate_folder(build, folder, log_path)
    _, valid, z, centres = truth_eval.read_raw_with_boxes(log_path, os.path.join(build, "lcmtypes", "python"))
    if not valid.any():
        evaluate.fail("the estimator finds no face in the independent face")
    return tuple(np.median(centres[valid], axis=0)), np.median(z[valid], axis=0)


def raised_cosine(s):
    return (1.0 - np.cos(np.pi * np.clip(s, 0.0, 1.0))) / 2.0


def trajectory(seed, seconds):
    """Holds, raised-cosine turns and slow pans (see the module's text), theta(t) at FPS and its moves."""
    rng = np.random.default_rng(seed)
    n = int(seconds * FPS)
    t = np.arange(n) / FPS
    theta = np.zeros(n)
    moves, angle, now = [], 0.0, 1.0  # a second of hold first: the unturned pose
    while now < seconds - 1.5:
        target = float(np.clip(angle + rng.choice([-1.0, 1.0]) * rng.uniform(5.0, 50.0), -50.0, 50.0))
        if rng.uniform() < 0.25:  # a slow pan instead of a turn
            target = float(np.clip(angle + rng.choice([-1.0, 1.0]) * rng.uniform(5.0, 15.0), -50.0, 50.0))
            duration = abs(target - angle) / rng.uniform(5.0, 15.0)
        else:
            duration = rng.uniform(0.2, 1.0)
        start, end = now, min(now + duration, seconds)
        inside = (t >= start) & (t < end)
        theta[inside] = angle + (target - angle) * raised_cosine((t[inside] - start) / duration)
        theta[t >= end] = target
        if abs(target - angle) >= 1.0 and end < seconds:
            moves.append(truth_motion.Move(start, end, angle, target))
        angle, now = target, end + rng.uniform(1.0, 3.0)
    return truth_motion.Trajectory(t, theta, moves)


def make_clips(build, out, image, centre, count, seconds):
    """count clips of the face along their own trajectories: truth_eval's clip specs."""
    specs = []
    axis = truth_clips.line_of_sight(centre, (image.shape[1], image.shape[0]))
    for k in range(count):
        label = f"astronaut_{k}"
        seed = 20261203 + k
        path = trajectory(seed, seconds)
        folder = os.path.join(out, "clips", label)
        log_path = os.path.join(out, "clips", label + ".lcmlog")
        if not os.path.exists(log_path):
            started = time.time()
            truth_clips.write_still_clip(folder, image, centre, path.theta, seed)
            truth_eval.estimate_folder(build, folder, log_path)
            log(f"{label}: {len(path.theta)} frames, {len(path.moves)} moves, {time.time() - started:.0f} s")
        specs.append((label, "astronaut", "still frame", path, log_path, [axis]))
    return specs


def report(rows, clips):
    """The defaults against each filter's best setting at equal still jitter, pooled over the clips."""
    pooled = truth_eval.pool(rows)
    by = {(p["filter"], p["setting"]): p for p in pooled}
    defaults = by[(evaluate.DEFAULTS_NAME, "as shipped")]
    raw = by[("raw", "-")]
    best = truth_eval.at_equal_jitter(pooled, defaults["jitter"])
    ordered = [raw, defaults] + [best[f] for f in evaluate.FILTER_NAMES if f in best]
    euro = best.get("1 euro")
    frames = sum(int(c.moving.sum()) for c in clips)
    lines = [truth_eval.table(ordered, f"An independent face and trajectories ({len(clips)} clips, {frames} moving "
                                       "frames): the defaults as shipped, each filter at no more still jitter"), ""]
    checks = {"rmse_ratio": defaults["rmse_moving"] / euro["rmse_moving"] if euro else float("nan"),
              "jitter_share": defaults["jitter"] / raw["jitter"],
              "overshoot_share": defaults["overshoot_share"]}
    goals = truth_eval.GOALS
    lines.append(f"- moving RMSE, defaults / best 1 euro at equal still jitter: **{checks['rmse_ratio']:.2f}x** "
                 f"(goal <= {goals['rmse_ratio']:.2f}: {'met' if checks['rmse_ratio'] <= goals['rmse_ratio'] else 'NOT met'})")
    lines.append(f"- still jitter, defaults / raw: **{100 * checks['jitter_share']:.0f} %** "
                 f"(goal <= {100 * goals['jitter_share']:.0f} %: {'met' if checks['jitter_share'] <= goals['jitter_share'] else 'NOT met'})")
    lines.append(f"- overshoot after a stop: **{100 * checks['overshoot_share']:.1f} %** of the move "
                 f"(goal <= {100 * goals['overshoot_share']:.0f} %: {'met' if checks['overshoot_share'] <= goals['overshoot_share'] else 'NOT met'})")
    lines.append(f"- onset delay: defaults {defaults['onset_ms']:.0f} ms, raw {raw['onset_ms']:.0f} ms")
    return "\n".join(lines) + "\n", euro


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(evaluate.ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(evaluate.ROOT, "out", "eval"))
    parser.add_argument("--clips", type=int, default=4)
    parser.add_argument("--seconds", type=float, default=30.0)
    args = parser.parse_args()
    build, out = os.path.abspath(args.build), os.path.join(os.path.abspath(args.out), "independent")
    work = os.path.join(out, "work")
    os.makedirs(os.path.join(out, "clips"), exist_ok=True)
    os.makedirs(work, exist_ok=True)
    image = fetch_face(os.path.join(out, "face"))
    centre, pose = face_centre(build, image, work)
    log(f"the face at ({centre[0]:.0f}, {centre[1]:.0f}) px, its own pose pitch {pose[0]:+.0f} yaw {pose[1]:+.0f} "
        f"roll {pose[2]:+.0f} deg")
    clips = [truth_eval.load(s, build) for s in make_clips(build, out, image, centre, args.clips, args.seconds)]
    grid = [("raw", "-", lambda: truth_eval._Identity())] + evaluate.settings_grid()
    rows, started = [], time.time()
    for k, clip in enumerate(clips):
        for setting in grid:
            roll = truth_eval.filter_output(build, clip, work, setting)
            rows.append({"clip": clip.name, "source": clip.source, "kind": clip.kind, "filter": setting[0],
                         "setting": setting[1], **truth_eval.clip_metrics(clip, roll)})
        log(f"{k + 1}/{len(clips)} clips through {len(grid)} filter settings ({time.time() - started:.0f} s)")
    text, euro = report(rows, clips)
    with open(os.path.join(out, "independent.md"), "w") as f:
        f.write(text)
    print(text)
    if euro is not None:
        grid_by = {(s[0], s[1]): s for s in grid}
        outputs = [("hkf defaults", truth_eval.filter_output(build, clips[0], work,
                                                             grid_by[(evaluate.DEFAULTS_NAME, "as shipped")])),
                   (f"1 euro ({euro['setting']})", truth_eval.filter_output(build, clips[0], work,
                                                                            grid_by[("1 euro", euro["setting"])]))]
        truth_eval.plot(clips[0], outputs, os.path.join(out, "independent_roll.png"))
        log(f"figure: {os.path.join(out, 'independent_roll.png')}")


if __name__ == "__main__":
    main()
