#!/usr/bin/env python3
"""A simulated drive with truth, measured through an empirical error model of
our own estimators, and the paper's figures on it (Figs. 6-8).

Error model, per estimator, all from our data:
- bias and spread per axis as functions of the labelled yaw: the signed error
  of `hkf-estimator --dataset` on ../shared/data/aflw2000, in yaw bins;
- faces not found: the share of AFLW2000 images without a face, per yaw bin,
  as dropouts of a few frames;
- frame-to-frame noise: the still jitter of the raw poses on the real clips
  (OUT/raw/*.lcmlog, made by evaluate.py).
The AFLW2000 spread less the frame-to-frame noise is a pose-dependent error
(a smooth random function of yaw and pitch): like a real estimator's, it is
the same each time the head comes back to the same pose.

The drive: 180 s at 30 fps of small head motion with mirror glances (yaw
-40/+50 deg), the rear-view mirror, the dashboard (pitch -20) and shoulder
checks to -80/+85 deg yaw, in minimum-jerk movements (peak ~250 deg/s).

Filters: the raw measurements; hkf-filter --offline with its defaults, with the
paper's filter (hkf_paper_settings) and its constant-R and no-loop-closure
variants, and every filter at
the setting evaluate.py chose on the real tuning clips (OUT/tuned_settings.json):
the drive is never used to tune. Per filter: RMSE against the truth per axis
(all frames with a measurement; at |yaw| >= 60; with the head within 5 deg of
the centre) and still jitter against the truth.

usage: sim_drive.py [--build DIR] [--out DIR] [--estimators mesh_pnp,whenet] [--seed N]
writes OUT/sim/{ESTIMATOR.aflw2000.csv, drive.ESTIMATOR.lcmlog, sim_rmse.md,
fig6_adaptive_r.png, fig7_loop_closure.png, fig8_estimators.png}"""
import argparse
import csv
import json
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import evaluate  # noqa: E402
import metrics  # noqa: E402
import peer_filters  # noqa: E402

FPS = 30.0
SECONDS = 180.0
YAW_EDGES = np.array([-99.0, -60.0, -30.0, -10.0, 10.0, 30.0, 60.0, 99.0])
DROPOUT_STAY = 0.8  # a missed face stays missed the next frame with this chance: runs of ~5 frames
LARGE_YAW = 60.0
CENTRE_RADIUS = 5.0
# (name, yaw, pitch, hold s) of the glances a driver makes
GLANCES = [("left mirror", -40.0, -5.0, 0.8), ("right mirror", 50.0, -5.0, 0.8), ("rear-view mirror", 25.0, 8.0, 0.7),
           ("dashboard", 0.0, -20.0, 0.6), ("left shoulder", -80.0, 0.0, 0.6), ("right shoulder", 85.0, 0.0, 0.6)]
DEFAULTS = "hkf defaults (calibrated)"
PAPER = "hkf paper (adaptive R + loop closure)"
PAPER_CONSTANT_R = "hkf paper, constant R"
PAPER_ADAPTIVE_R = "hkf paper, adaptive R"
FIXED_VARIANTS = {DEFAULTS: [], PAPER: evaluate.PAPER_OPTIONS,  # name -> hkf-filter --set options
                  PAPER_CONSTANT_R: evaluate.PAPER_OPTIONS + ["noise_mode=constant", "loop_closure=off"],
                  PAPER_ADAPTIVE_R: evaluate.PAPER_OPTIONS + ["noise_mode=adaptive", "loop_closure=off"]}


def signed_errors(labels_path, predictions_path):
    """(labelled angles (n, 3), signed errors (n, 3), found (n,)) in hkf's convention, |angles| <= 99."""
    with open(predictions_path) as f:
        predicted = {r["image"]: r for r in csv.DictReader(f)}
    labels, errors, found = [], [], []
    with open(labels_path) as f:
        for r in csv.DictReader(f):
            label = np.array([float(r["pitch_deg"]), float(r["yaw_deg"]), -float(r["roll_deg"])])
            if np.abs(label).max() > 99.0:
                continue
            p = predicted.get(r["image"])
            labels.append(label)
            found.append(p is not None)
            guess = label if p is None else np.array([float(p["pitch_deg"]), float(p["yaw_deg"]), float(p["roll_deg"])])
            errors.append(metrics.wrap180(guess - label))
    return np.array(labels), np.array(errors), np.array(found)


def frame_noise(raw_logs, types):
    """Per-axis standard deviation of the frame-to-frame noise: still jitter of the raw poses / sqrt(2)."""
    squares, pairs = np.zeros(3), 0
    for log in raw_logs:
        _, t, valid, z = evaluate.read_raw(log, types)
        tv, zv = t[valid], z[valid]
        ref = metrics.reference(tv, zv)
        still, _ = metrics.masks(tv, ref)
        both = still[1:] & still[:-1]
        d = np.diff(metrics.wrap180(zv - ref), axis=0)[both]
        squares += (d ** 2).sum(axis=0)
        pairs += len(d)
    return np.sqrt(squares / max(pairs, 1) / 2.0), pairs


def error_model(build, out, estimator, types):
    data = os.path.join(evaluate.ROOT, "..", "shared", "data", "aflw2000")
    predictions = os.path.join(out, f"{estimator}.aflw2000.csv")
    if not os.path.exists(predictions):
        result = subprocess.run([os.path.join(build, "estimator", "hkf-estimator"), "--dataset", data, "--crop", "labels", "--model",
                                 estimator, "--second-model", "none", "--predictions", predictions + ".part"], capture_output=True, text=True)
        if result.returncode != 0:
            evaluate.fail(f"hkf-estimator --dataset ({estimator}) exited {result.returncode}: {result.stderr[-400:]}")
        os.replace(predictions + ".part", predictions)
    labels, errors, found = signed_errors(os.path.join(data, "labels.csv"), predictions)
    raw_logs = [evaluate.raw_log(build, os.path.dirname(out), clip, estimator) for clip in evaluate.clips()]
    fast, pairs = frame_noise(raw_logs, types)
    index = np.clip(np.digitize(labels[:, 1], YAW_EDGES) - 1, 0, len(YAW_EDGES) - 2)
    bins = []
    for b in range(len(YAW_EDGES) - 1):
        inside = index == b
        kept = inside & found
        bins.append({"yaw": float(np.mean(labels[inside, 1])), "images": int(inside.sum()),
                     "found": float(kept.sum() / inside.sum()), "bias": errors[kept].mean(axis=0),
                     "spread": errors[kept].std(axis=0)})
    return {"bins": bins, "fast": fast, "still_pairs": pairs}


def min_jerk(s):
    return s * s * s * (10.0 - 15.0 * s + 6.0 * s * s)


def drive(seed):
    """(t, truth (n, 3), glance name per frame or '') of the simulated drive."""
    rng = np.random.default_rng(seed)
    n = int(SECONDS * FPS)
    t = np.arange(n) / FPS
    # small motion around the centre: low-passed noise, about +-2 deg
    wander = np.cumsum(rng.normal(0.0, 1.0, (n, 3)), axis=0)
    kernel = np.hanning(int(2 * FPS))
    wander = np.stack([np.convolve(w - np.linspace(w[0], w[-1], n), kernel / kernel.sum(), "same") for w in wander.T], 1)
    wander *= 2.0 / max(wander.std(), 1e-9)
    offset = np.zeros((n, 3))
    label = [""] * n
    i = int(2 * FPS)
    while i < n - 4 * FPS:
        name, yaw, pitch, hold = GLANCES[rng.integers(len(GLANCES))]
        target = np.array([pitch, yaw, -0.08 * yaw]) + rng.normal(0.0, [2.0, 4.0, 1.0])
        move = 0.25 + np.abs(target).max() / 250.0
        steps = [(move, 0.0, 1.0), (hold + rng.uniform(-0.2, 0.2), 1.0, 1.0), (move, 1.0, 0.0)]
        for duration, start, end in steps:
            m = int(duration * FPS)
            s = min_jerk(np.arange(1, m + 1) / m)
            offset[i:i + m] = target * (start + (end - start) * s)[:, None]
            label[i:i + m] = [name] * m
            i += m
        i += int(rng.uniform(2.0, 6.0) * FPS)
    return t, wander + offset, label


def measure(truth, model, seed):
    """(z, valid): the truth through the error model."""
    rng = np.random.default_rng(seed)
    yaw = truth[:, 1]
    centres = [b["yaw"] for b in model["bins"]]
    bias = np.stack([np.interp(yaw, centres, [b["bias"][a] for b in model["bins"]]) for a in range(3)], 1)
    spread = np.stack([np.interp(yaw, centres, [b["spread"][a] for b in model["bins"]]) for a in range(3)], 1)
    found = np.interp(yaw, centres, [b["found"] for b in model["bins"]])
    pose_spread = np.sqrt(np.maximum(spread ** 2 - model["fast"] ** 2, 0.0))
    # a smooth unit-variance random function of (yaw, pitch) per axis: sum of 6 random plane waves
    waves = rng.uniform(1.0 / 60.0, 1.0 / 20.0, (3, 6, 2)) * rng.choice([-1.0, 1.0], (3, 6, 2)) * 2 * np.pi
    phases = rng.uniform(0, 2 * np.pi, (3, 6))
    field = np.stack([np.sqrt(2.0 / 6.0) * np.cos(truth[:, 1:2] * waves[a, :, 0] + truth[:, 0:1] * waves[a, :, 1]
                                                   + phases[a]).sum(axis=1) for a in range(3)], 1)
    z = truth + bias + pose_spread * field + rng.normal(0.0, 1.0, truth.shape) * model["fast"]
    z[:, 1] = metrics.wrap180(z[:, 1])
    valid = np.ones(len(z), dtype=bool)
    for i in range(len(z)):  # dropouts in runs: stationary rate 1 - found
        p = 1.0 - found[i]
        enter = p * (1.0 - DROPOUT_STAY) / max(1.0 - p, 1e-6)
        valid[i] = not (rng.random() < (DROPOUT_STAY if i and not valid[i - 1] else enter))
    return z, valid


def write_log(path, t, z, valid, estimator, types):
    import lcm
    sys.path.insert(0, types)
    from hkf import head_pose_measurement_t
    log = lcm.EventLog(path, "w", overwrite=True)
    start = 1_700_000_000_000_000
    for i in range(len(t)):
        m = head_pose_measurement_t()
        m.utime = start + int(round(t[i] * 1e6))
        m.seq = i
        m.model = estimator
        m.valid = bool(valid[i])
        m.pitch, m.yaw, m.roll = (float(v) for v in z[i]) if valid[i] else (0.0, 0.0, 0.0)
        m.face_box = [0.0] * 4
        m.detection_score = 0.9 if valid[i] else 0.0
        m.inference_us = 0
        log.write_event(m.utime, "HEAD_POSE_RAW", m.encode())
    log.close()
    return start + np.round(t * 1e6).astype(np.int64)


def filters_for(estimator, tuned):
    """(name, hkf --set list or peer factory) of every filter compared on the drive."""
    grid = {(f, s): how for f, s, how in evaluate.settings_grid()}
    chosen = list(FIXED_VARIANTS.items())
    for name in evaluate.FILTER_NAMES:
        setting = tuned[estimator].get(name)
        if setting is not None:
            chosen.append((f"{name} ({setting})", grid[(name, setting)]))
    chosen.append(("1 euro (recommended)", grid[("1 euro (recommended)",
                                                 "min_cutoff %g Hz, beta %g" % evaluate.ONE_EURO_RECOMMENDED)]))
    return chosen


def run_filter(how, build, log, work, utime, t, z, valid):
    if isinstance(how, list):
        posteriors = evaluate.run_hkf(build, log, work, how)
        return np.array([posteriors.get(int(u), (np.nan,) * 3) for u in utime])
    made = how()
    filt, tick = made if isinstance(made, tuple) else (made, None)
    return peer_filters.run(filt, t, z, valid, tick)


def scores(output, truth, valid):
    """RMSE per axis over the frames with a measurement: all, |yaw| >= LARGE_YAW, near the centre;
    still jitter against the truth (RMS frame-to-frame change of the error where the truth is still)."""
    keep = valid & ~np.isnan(output).any(axis=1)
    large = keep & (np.abs(truth[:, 1]) >= LARGE_YAW)
    centre = keep & (np.linalg.norm(truth, axis=1) <= CENTRE_RADIUS)
    still = np.zeros(len(truth), dtype=bool)
    speed = np.linalg.norm(np.gradient(truth, axis=0), axis=1) * FPS
    still[1:] = (speed[1:] < 5.0) & (speed[:-1] < 5.0) & keep[1:] & keep[:-1]
    err = metrics.wrap180(output - truth)
    jitter = float(np.sqrt(np.mean(np.diff(err, axis=0)[still[1:]] ** 2))) if still.any() else float("nan")
    return {"all": metrics.rmse(output[keep], truth[keep]), "large": metrics.rmse(output[large], truth[large]),
            "centre": metrics.rmse(output[centre], truth[centre]), "jitter": jitter}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    parser.add_argument("--build", default=os.path.join(evaluate.ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(evaluate.ROOT, "out", "eval"))
    parser.add_argument("--estimators", default="mesh_pnp,whenet")
    parser.add_argument("--seed", type=int, default=7)
    args = parser.parse_args()
    build, out = os.path.abspath(args.build), os.path.join(os.path.abspath(args.out), "sim")
    types = os.path.join(build, "lcmtypes", "python")
    tuned_path = os.path.join(os.path.dirname(out), "tuned_settings.json")
    if not os.path.exists(tuned_path):
        evaluate.fail(f"no {tuned_path}: run evaluate.py first (./run eval)")
    tuned = json.load(open(tuned_path))
    os.makedirs(os.path.join(out, "work"), exist_ok=True)
    t, truth, glance = drive(args.seed)
    lines, runs = [], {}
    for estimator in [e for e in args.estimators.split(",") if e]:
        model = error_model(build, out, estimator, types)
        z, valid = measure(truth, model, args.seed + 1)
        log = os.path.join(out, f"drive.{estimator}.lcmlog")
        utime = write_log(log, t, z, valid, estimator, types)
        print(f"  {estimator}: error model from {sum(b['images'] for b in model['bins'])} AFLW2000 images and "
              f"{model['still_pairs']} still frame pairs of the real clips; drive {len(t)} frames, "
              f"{int(valid.sum())} with a face", flush=True)
        lines.append(f"\n{estimator} error model (AFLW2000 by labelled yaw; frame-to-frame noise "
                     f"{', '.join(f'{v:.2f}' for v in model['fast'])} deg in pitch, yaw, roll):\n")
        lines.append("| labelled yaw | images | faces found | bias pitch, yaw, roll | spread pitch, yaw, roll |")
        lines.append("| ---: | ---: | ---: | --- | --- |")
        for b in model["bins"]:
            lines.append(f"| {b['yaw']:+.0f} deg | {b['images']} | {100 * b['found']:.0f} % | "
                         f"{', '.join(f'{v:+.1f}' for v in b['bias'])} | {', '.join(f'{v:.1f}' for v in b['spread'])} |")
        lines.append(f"\n{estimator} on the drive: RMSE against the truth, deg (pitch / yaw / roll), over the "
                     f"{int(valid.sum())} frames with a measurement; at |yaw| >= {LARGE_YAW:.0f}; within "
                     f"{CENTRE_RADIUS:.0f} deg of the centre; still jitter against the truth\n")
        lines.append("| filter | RMSE all | RMSE at large yaw | RMSE near the centre | still jitter |")
        lines.append("| --- | --- | --- | --- | ---: |")
        results = {"raw": z.copy()}
        results["raw"][~valid] = np.nan
        for name, how in filters_for(estimator, tuned):
            results[name] = run_filter(how, build, log, os.path.join(out, "work"), utime, t, z, valid)
        for name, output in results.items():
            s = scores(output, truth, valid)
            cells = [" / ".join(f"{v:.2f}" for v in s[k]) for k in ("all", "large", "centre")]
            lines.append(f"| {name} | {cells[0]} | {cells[1]} | {cells[2]} | {s['jitter']:.3f} deg |")
        runs[estimator] = (z, valid, results)
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out, "sim_rmse.md"), "w") as f:
        f.write(text)
    print(text)
    return out, t, truth, glance, runs  # for sim_figures.py, which draws them


if __name__ == "__main__":
    main()
