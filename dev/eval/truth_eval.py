#!/usr/bin/env python3
"""Every filter against exact truth on real faces.

Truth clips: from each clip in ../shared/data/videos, two real frames - the
most frontal and the most turned face the estimator found - each turned in the
image plane along a driver trajectory (dev/eval/truth_motion.py: holds,
glances of 10-40 deg at up to 300 deg/s and back, a drift, a sine, a tremor),
with fresh sensor noise and JPEG on every frame (truth_clips.py). An in-plane
turn of theta about the face centre is the head turned by theta about the line
of sight through it: a roll of theta for a frontal face in the middle, and
truth_clips.truth_angles(theta, own pose, that line) for any face, the own pose
being the estimator's median reading over the frames where theta is 0. The real-motion variant turns a whole real clip the
same way; its own pose is the clip's raw pose low-passed without phase shift
(metrics.reference), frame by frame.

Each truth clip goes through hkf-estimator (default model) as an image folder
at 30 fps, then through every filter and setting of dev/eval/evaluate.py's
sweep. Metrics (truth_metrics.py): still jitter, roll RMSE on moving and still
frames, overshoot after a stop, onset delay, settling time. Each filter is
compared at the defaults' still jitter: its best moving RMSE among its
settings whose jitter is no higher.

The defaults were tuned on evaluate.py's TUNING_CLIPS; the tables give the
truth clips made from the other clips (held out) and from all.

usage: truth_eval.py [--build DIR] [--out DIR] [--clips N] [--frames-per-clip K] [--glances G]
writes OUT/truth/{truth_sweep.csv,truth.md,truth_roll.png} and the clips and
their raw logs under OUT/truth/clips (made once, reused).
"""
import argparse
import csv
import os
import subprocess
import sys
import time
import zlib

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import evaluate  # noqa: E402
import metrics  # noqa: E402
import peer_filters  # noqa: E402
import truth_clips  # noqa: E402
import truth_metrics  # noqa: E402
import truth_motion  # noqa: E402

FPS = 30.0
ESTIMATOR = "mesh_pnp"  # the default model
GOALS = {  # what the filter should reach on held-out clips (docs/evaluation.md states them)
    "rmse_ratio": 0.70,       # defaults' moving RMSE / best 1 euro's at equal jitter
    "jitter_share": 0.25,     # defaults' still jitter / raw's
    "overshoot_share": 0.05,  # of the move
    "onset_frames": 1.0,      # more than raw
}
ROLL = 2


def log(message):
    print(f"truth_eval: {message}", flush=True)


def read_raw_with_boxes(path, types_dir):
    """(utime, valid, angles (n, 3), face centres (n, 2)) of a raw log."""
    import lcm
    sys.path.insert(0, types_dir)
    from hkf import head_pose_measurement_t
    utime, valid, z, centre = [], [], [], []
    for event in lcm.EventLog(path, "r"):
        if event.channel != "HEAD_POSE_RAW":
            continue
        m = head_pose_measurement_t.decode(event.data)
        if utime and m.utime == utime[-1]:
            continue  # a second model's measurement of the same frame
        utime.append(m.utime)
        valid.append(bool(m.valid))
        z.append((m.pitch, m.yaw, m.roll))
        centre.append(((m.face_box[0] + m.face_box[2]) / 2.0, (m.face_box[1] + m.face_box[3]) / 2.0))
    return np.array(utime, dtype=np.int64), np.array(valid), np.array(z, float), np.array(centre, float)


def estimate_folder(build, folder, log_path):
    """hkf-estimator on an image folder at FPS; the raw log, made once."""
    if os.path.exists(log_path):
        return log_path
    result = subprocess.run([os.path.join(build, "estimator", "hkf-estimator"), "--source", folder, "--fps", f"{FPS:g}",
                             "--model", ESTIMATOR, "--second-model", "none", "--lcm-url", f"file://{log_path}.part?mode=w"],
                            capture_output=True, text=True)
    if result.returncode != 0:
        evaluate.fail(f"hkf-estimator on {folder} exited {result.returncode}: {result.stderr.strip()[-400:]}")
    os.replace(log_path + ".part", log_path)
    return log_path


class TruthClip:
    """One clip: its name, source clip, kind, the truth (deg, per frame), the raw measurements
    (capture stamps utime, frame times t) and the raw log they are in."""

    def __init__(self, name, source, kind, trajectory, truth, log, utime, t, valid, z, still, moving, to_truth):
        self.name, self.source, self.kind = name, source, kind
        self.trajectory, self.truth, self.log = trajectory, truth, log
        self.utime, self.t, self.valid, self.z = utime, t, valid, z
        self.still, self.moving, self.to_truth = still, moving, to_truth


def make_still_clips(build, out, clip, frames_per_clip, glances):
    """The clip's most frontal and most turned faces, each turned along a trajectory."""
    name = os.path.splitext(os.path.basename(clip))[0]
    raw = evaluate.raw_log(build, out, clip, ESTIMATOR)
    utime, valid, z, centres = read_raw_with_boxes(raw, os.path.join(build, "lcmtypes", "python"))
    found = np.flatnonzero(valid)
    if found.size == 0:
        return []
    order = found[np.argsort(np.abs(z[found, 1]))]
    picks = [int(order[0]), int(order[-1])][:frames_per_clip]
    if frames_per_clip > 2:
        picks += [int(i) for i in order[np.linspace(1, len(order) - 2, frames_per_clip - 2).astype(int)]]
    images = truth_clips.read_frames(clip, picks)
    made = []
    for k, (index, image) in enumerate(zip(picks, images)):
        label = f"{name}_f{index:04d}"
        seed = zlib.crc32(label.encode())
        trajectory = truth_motion.driver_trajectory(seed, FPS, glances)
        folder = os.path.join(out, "truth", "clips", label)
        log_path = os.path.join(out, "truth", "clips", label + ".lcmlog")
        if not os.path.exists(log_path):
            started = time.time()
            truth_clips.write_still_clip(folder, image, centres[index], trajectory.theta, seed)
            estimate_folder(build, folder, log_path)
            log(f"{label}: {len(trajectory.theta)} frames (face yaw {z[index, 1]:+.0f} deg), "
                f"{time.time() - started:.0f} s")
        axis = truth_clips.line_of_sight(centres[index], (image.shape[1], image.shape[0]))
        made.append((label, name, "still frame", trajectory, log_path, [axis]))
    return made


def make_moving_clip(build, out, clip, glances):
    """The whole clip, its own motion kept, turned along a trajectory as long as it."""
    name = os.path.splitext(os.path.basename(clip))[0]
    raw = evaluate.raw_log(build, out, clip, ESTIMATOR)
    utime, valid, z, centres = read_raw_with_boxes(raw, os.path.join(build, "lcmtypes", "python"))
    label = f"{name}_moving"
    seed = zlib.crc32(label.encode())
    trajectory = truth_motion.driver_trajectory(seed, FPS, glances)
    n = min(len(utime), len(trajectory.theta))
    trajectory = truth_motion.Trajectory(trajectory.t[:n], trajectory.theta[:n],
                                         [m for m in trajectory.moves if m.t1 < trajectory.t[n - 1]],
                                         trajectory.segments)
    log_path = os.path.join(out, "truth", "clips", label + ".lcmlog")
    if not os.path.exists(log_path):
        frames = truth_clips.read_frames(clip)[:n]
        filled = centres.copy()  # frames without a face: the last face's centre
        for i in range(len(filled)):
            if not valid[i]:
                filled[i] = filled[i - 1] if i > 0 else (frames[0].shape[1] / 2.0, frames[0].shape[0] / 2.0)
        folder = os.path.join(out, "truth", "clips", label)
        truth_clips.write_moving_clip(folder, frames, filled[:n], trajectory.theta, seed)
        estimate_folder(build, folder, log_path)
        log(f"{label}: {n} frames of the real clip turned")
    # the clip's own pose, unturned: low-passed without phase shift; what that removed is its error's scale
    tv = (utime[:n] - utime[0]) / 1e6
    keep = valid[:n]
    own = np.full((n, 3), np.nan)
    if keep.sum() > 30:
        ref = metrics.reference(tv[keep], z[:n][keep])
        own[keep] = ref
        reference_noise = float(np.sqrt(np.mean((z[:n][keep, ROLL] - ref[:, ROLL]) ** 2)))
    else:
        reference_noise = float("nan")
    size = truth_clips.read_frames(clip, [0])[0].shape
    axes = [truth_clips.line_of_sight(c, (size[1], size[0])) for c in centres[:n]]
    return (label, name, "real motion", trajectory, log_path, axes), own, reference_noise


def load(spec, build, own_pose=None):
    label, source, kind, trajectory, log_path, axes = spec
    utime, valid, z, _ = read_raw_with_boxes(log_path, os.path.join(build, "lcmtypes", "python"))
    n = min(len(utime), len(trajectory.theta))
    t = (utime[:n] - utime[0]) / 1e6
    valid, z = valid[:n], z[:n]
    theta = trajectory.theta[:n]
    if own_pose is None:
        unturned = valid & (theta == 0.0)
        base = np.median(z[unturned if unturned.any() else valid], axis=0)
        truth = truth_clips.truth_angles(theta, base, axes[0])[:, ROLL]
        still = truth_motion.still_mask(truth_motion.Trajectory(t, theta))

        def to_truth(angle):
            return truth_clips.truth_angles(angle, base, axes[0])[0, ROLL]
    else:
        truth = np.array([truth_clips.truth_angles(a, p, axis)[0, ROLL] if np.isfinite(p).all() else np.nan
                          for a, p, axis in zip(theta, own_pose[:n], axes)])
        still = np.zeros(n, dtype=bool)  # a real head is never exactly still
        to_truth = None  # no step metrics: the head's own motion goes on during a move
    speed = np.abs(np.gradient(np.nan_to_num(truth), t))
    return TruthClip(label, source, kind, trajectory, truth, log_path, utime[:n], t, valid, z, still, speed > 10.0,
                     to_truth)


def filter_output(build, clip, work, setting):
    """The filter's roll at every frame (NaN where it has none)."""
    name, _, how = setting
    if isinstance(how, list):
        posteriors = evaluate.run_hkf(build, clip.log, work, how)
        out = np.array([posteriors.get(int(u), (np.nan,) * 3) for u in clip.utime], float)
    else:
        made = how()
        filt, tick = made if isinstance(made, tuple) else (made, None)
        out = peer_filters.run(filt, clip.t, clip.z, clip.valid, tick=tick)
    return out[:, ROLL]


def clip_metrics(clip, roll):
    row = {"jitter": truth_metrics.still_jitter(roll, clip.still),
           "still_pairs": int((clip.still[1:] & clip.still[:-1]).sum()),
           "rmse_moving": truth_metrics.rmse(roll, clip.truth, clip.moving & np.isfinite(roll)),
           "moving": int((clip.moving & np.isfinite(roll)).sum()),
           "rmse_still": truth_metrics.rmse(roll, clip.truth, clip.still & np.isfinite(roll))}
    moves = (truth_metrics.moves_metrics(clip.t, roll, clip.truth, clip.trajectory.moves, clip.to_truth)
             if clip.to_truth is not None else [])
    for key in ("overshoot", "overshoot_share", "onset_delay", "settle"):
        values = [m[key] for m in moves if np.isfinite(m[key])]
        row[key] = float(np.mean(values)) if values else float("nan")
        row[key + "_n"] = len(values)
    row["overshoot_max"] = float(max([m["overshoot"] for m in moves if np.isfinite(m["overshoot"])], default=np.nan))
    return row


def pool(rows):
    """Per (filter, setting): jitter pooled over still pairs, RMSE over frames, move metrics over moves."""
    groups = {}
    for r in rows:
        groups.setdefault((r["filter"], r["setting"]), []).append(r)
    result = []
    for (name, setting), rs in groups.items():
        def weighted_rms(key, weight):
            w = np.array([r[weight] for r in rs], float)
            v = np.array([r[key] for r in rs], float)
            ok = (w > 0) & np.isfinite(v)
            return float(np.sqrt(np.sum(w[ok] * v[ok] ** 2) / w[ok].sum())) if ok.any() else float("nan")

        def moves_mean(key):
            w = np.array([r[key + "_n"] for r in rs], float)
            v = np.array([r[key] for r in rs], float)
            ok = (w > 0) & np.isfinite(v)
            return float(np.sum(w[ok] * v[ok]) / w[ok].sum()) if ok.any() else float("nan")

        result.append({"filter": name, "setting": setting, "jitter": weighted_rms("jitter", "still_pairs"),
                       "rmse_moving": weighted_rms("rmse_moving", "moving"),
                       "rmse_still": weighted_rms("rmse_still", "still_pairs"),
                       "overshoot": moves_mean("overshoot"), "overshoot_share": moves_mean("overshoot_share"),
                       "overshoot_max": float(np.nanmax([r["overshoot_max"] for r in rs])),
                       "onset_ms": 1000.0 * moves_mean("onset_delay"), "settle_ms": 1000.0 * moves_mean("settle")})
    return result


def at_equal_jitter(pooled, jitter):
    """Per filter: the setting with the lowest moving RMSE among those no more jittery than `jitter`."""
    best = {}
    for p in pooled:
        if not (p["jitter"] <= jitter * 1.0001):
            continue
        if p["filter"] not in best or p["rmse_moving"] < best[p["filter"]]["rmse_moving"]:
            best[p["filter"]] = p
    return best


def table(rows, title):
    lines = [f"### {title}", "",
             "| filter | setting | still jitter (deg/frame) | RMSE moving (deg) | RMSE still (deg) | overshoot (deg, mean / max) "
             "| overshoot (share of the move) | onset delay (ms) | settling (ms) |",
             "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for p in rows:
        lines.append(f"| {p['filter']} | {p['setting']} | {p['jitter']:.3f} | {p['rmse_moving']:.2f} | {p['rmse_still']:.2f} "
                     f"| {p['overshoot']:.2f} / {p['overshoot_max']:.1f} | {100 * p['overshoot_share']:.1f} % "
                     f"| {p['onset_ms']:.0f} | {p['settle_ms']:.0f} |")
    return "\n".join(lines) + "\n"


def report(rows, clips):
    held = {c.name for c in clips if c.source not in evaluate.TUNING_CLIPS and c.kind == "still frame"}
    tuned = {c.name for c in clips if c.source in evaluate.TUNING_CLIPS and c.kind == "still frame"}
    sections, summary = [], {}
    for label, names in (("held out (truth clips from clips the defaults were not tuned on)", held),
                         ("tuning clips", tuned), ("all still-frame truth clips", held | tuned)):
        if not names:
            continue
        pooled = pool([r for r in rows if r["clip"] in names])
        by = {(p["filter"], p["setting"]): p for p in pooled}
        defaults = by[(evaluate.DEFAULTS_NAME, "as shipped")]
        raw = by[("raw", "-")]
        best = at_equal_jitter(pooled, defaults["jitter"])
        ordered = [raw, defaults] + [best[f] for f in evaluate.FILTER_NAMES + ["1 euro (recommended)"] if f in best]
        frames = sum(c.moving.sum() for c in clips if c.name in names)
        absent = []
        for name in evaluate.FILTER_NAMES:
            mine = [p for p in pooled if p["filter"] == name]
            if name not in best and mine:
                low = min(mine, key=lambda p: p["jitter"])
                absent.append(f"{name} (its stillest setting, {low['setting']}: jitter {low['jitter']:.3f}, "
                              f"RMSE moving {low['rmse_moving']:.2f})")
        sections.append(table(ordered, f"{label}: {len(names)} clips, {frames} moving frames; each filter at "
                                       f"the defaults' still jitter ({defaults['jitter']:.3f} deg/frame) or below")
                        + (f"\nNo setting this still: {'; '.join(absent)}.\n" if absent else ""))
        summary[label] = (defaults, raw, best.get("1 euro"))
    first = next(iter(summary))
    held_defaults, held_raw, held_euro = summary[first]
    goals = [f"### Goals ({first.split(' (')[0]})", ""]
    if held_euro is not None:
        ratio = held_defaults["rmse_moving"] / held_euro["rmse_moving"]
        goals.append(f"- moving RMSE, defaults / best 1 euro at equal jitter: {held_defaults['rmse_moving']:.2f} / "
                     f"{held_euro['rmse_moving']:.2f} = {ratio:.2f} (goal <= {GOALS['rmse_ratio']:.2f}): "
                     f"{'met' if ratio <= GOALS['rmse_ratio'] else 'NOT met'}")
    share = held_defaults["jitter"] / held_raw["jitter"]
    goals.append(f"- still jitter, defaults / raw: {held_defaults['jitter']:.3f} / {held_raw['jitter']:.3f} = "
                 f"{100 * share:.0f} % (goal <= {100 * GOALS['jitter_share']:.0f} %): "
                 f"{'met' if share <= GOALS['jitter_share'] else 'NOT met'}")
    goals.append(f"- overshoot: {100 * held_defaults['overshoot_share']:.1f} % of the move on average, "
                 f"{held_defaults['overshoot_max']:.1f} deg at most (goal <= 5 %): "
                 f"{'met' if held_defaults['overshoot_share'] <= GOALS['overshoot_share'] else 'NOT met'}")
    onset = (held_defaults["onset_ms"] - held_raw["onset_ms"]) / (1000.0 / FPS)
    goals.append(f"- onset delay: {held_defaults['onset_ms']:.0f} ms vs raw {held_raw['onset_ms']:.0f} ms = "
                 f"{onset:+.1f} frames (goal <= +1): {'met' if onset <= GOALS['onset_frames'] else 'NOT met'}")
    text = "## Truth by construction: roll on real faces\n\n" + "\n".join(goals) + "\n\n" + "\n".join(sections)
    return text


FRONTIER_SHARES = [0.05, 0.08, 0.10, 0.15, 0.20, 0.25, 0.30]  # still jitter as a share of raw's
FRONTIER_FAMILIES = [(evaluate.TWO_MODELS_NAME, "C3", "o"), ("1 euro", "C0", "s"), ("hkf adaptive R", "C2", "^")]


def front_points(pooled, name):
    """(jitter, RMSE moving) of a family's settings that no other of its settings beats on both."""
    points = sorted((p["jitter"], p["rmse_moving"]) for p in pooled if p["filter"] == name and np.isfinite(p["rmse_moving"]))
    front, best = [], float("inf")
    for jitter, rmse in points:
        if rmse < best:
            front.append((jitter, rmse))
            best = rmse
    return front


def frontier_report(groups):
    """The jitter-RMSE frontier: per group of clips, each family's best moving RMSE at a still jitter of at most
    each share of raw's, and hkf's ratio to the 1 euro filter's there."""
    lines = ["### The jitter-RMSE frontier: the best moving RMSE (deg) at a still jitter of at most a share of raw's", "",
             "| clips | filter | " + " | ".join(f"<= {100 * s:g} %" for s in FRONTIER_SHARES) + " |",
             "| --- | --- | " + " | ".join("---:" for _ in FRONTIER_SHARES) + " |"]
    for label, pooled in groups:
        raw = next(p for p in pooled if p["filter"] == "raw")
        best = {}
        for name, _, _ in FRONTIER_FAMILIES:
            row = []
            for share in FRONTIER_SHARES:
                fits = [p["rmse_moving"] for p in pooled if p["filter"] == name and p["jitter"] <= share * raw["jitter"]]
                row.append(min(fits) if fits else float("nan"))
            best[name] = row
            lines.append(f"| {label} | {name} | " + " | ".join("-" if np.isnan(v) else f"{v:.2f}" for v in row) + " |")
        ratio = [a / b if np.isfinite(a) and np.isfinite(b) else float("nan")
                 for a, b in zip(best[evaluate.TWO_MODELS_NAME], best["1 euro"])]
        lines.append(f"| {label} | hkf / 1 euro | " + " | ".join("-" if np.isnan(v) else f"**{v:.2f}**" for v in ratio) + " |")
    return "\n".join(lines) + "\n"


def plot_frontier(groups, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(groups), figsize=(6.5 * len(groups), 4.6), squeeze=False)
    for ax, (label, pooled) in zip(axes[0], groups):
        raw = next(p for p in pooled if p["filter"] == "raw")
        for name, colour, marker in FRONTIER_FAMILIES:
            cloud = [(p["jitter"] / raw["jitter"], p["rmse_moving"]) for p in pooled if p["filter"] == name]
            ax.plot([c[0] for c in cloud], [c[1] for c in cloud], marker, color=colour, alpha=0.18, ms=4)
            front = front_points(pooled, name)
            ax.plot([j / raw["jitter"] for j, _ in front], [r for _, r in front], "-" + marker, color=colour, ms=4,
                    label=f"{name} (front)")
        mine = next(p for p in pooled if p["filter"] == evaluate.DEFAULTS_NAME)
        ax.plot([mine["jitter"] / raw["jitter"]], [mine["rmse_moving"]], "*", color="k", ms=14, label="hkf defaults")
        ax.axvline(0.25, color="0.5", ls=":", lw=1)
        ax.set_xlim(0, 0.6)
        ax.set_ylim(0, 3.0)
        ax.set_xlabel("still jitter, share of raw's")
        ax.set_ylabel("roll RMSE on moving frames, deg")
        ax.set_title(label)
        ax.grid(alpha=0.3)
    axes[0][0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def moving_report(moving_clips, rows_by_clip, chosen):
    lines = ["### Real-motion variant: whole real clips turned along a trajectory", "",
             "| clip | frames | reference error (RMS of raw - its low-pass, unturned clip) | raw RMSE moving | "
             + " | ".join(f"{f} RMSE moving" for f, _ in chosen) + " |",
             "| --- | ---: | ---: | ---: | " + " | ".join("---:" for _ in chosen) + " |"]
    for clip, noise in moving_clips:
        r = rows_by_clip[clip.name]
        lines.append(f"| {clip.name} | {len(clip.t)} | {noise:.2f} deg | {r[('raw', '-')]['rmse_moving']:.2f} | "
                     + " | ".join(f"{r[key]['rmse_moving']:.2f}" for _, key in chosen) + " |")
    return "\n".join(lines) + "\n"


def plot(clip, outputs, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    moves = clip.trajectory.moves
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.5))
    for ax, move in zip(axes, [max(moves, key=lambda m: abs(m.size)), moves[min(1, len(moves) - 1)]]):
        window = (clip.t >= move.t0 - 0.4) & (clip.t <= move.t1 + 1.2)
        ax.plot(clip.t[window], clip.truth[window], "k-", lw=2.5, label="truth")
        ax.plot(clip.t[window], np.where(clip.valid, clip.z[:, ROLL], np.nan)[window], ".", color="0.6", label="raw")
        for (label, roll), style in zip(outputs, ["C3-", "C0-", "C2--"]):
            ax.plot(clip.t[window], roll[window], style, lw=1.6, label=label)
        ax.set_xlabel("s")
        ax.set_ylabel("roll, deg")
        ax.set_title(f"{clip.name}: a {move.size:+.0f} deg move in {1000 * (move.t1 - move.t0):.0f} ms")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(evaluate.ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(evaluate.ROOT, "out", "eval"))
    parser.add_argument("--clips", type=int, default=0, help="only the first N clips (0: all)")
    parser.add_argument("--frames-per-clip", type=int, default=2)
    parser.add_argument("--glances", type=int, default=4)
    parser.add_argument("--moving-clips", type=int, default=2, help="real-motion variants (0: none)")
    args = parser.parse_args()
    build, out = os.path.abspath(args.build), os.path.abspath(args.out)
    sources = [c for c in evaluate.clips() if "shared" in c]
    if args.clips:
        sources = sources[:args.clips]
    os.makedirs(os.path.join(out, "truth", "clips"), exist_ok=True)
    work = os.path.join(out, "truth", "work")
    os.makedirs(work, exist_ok=True)
    log(f"building truth clips from {len(sources)} clips (made once, reused)")
    specs = []
    for clip in sources:
        specs += make_still_clips(build, out, clip, args.frames_per_clip, args.glances)
    moving = []
    for clip in [c for c in sources if os.path.splitext(os.path.basename(c))[0] not in evaluate.TUNING_CLIPS][
            :args.moving_clips]:
        spec, own, noise = make_moving_clip(build, out, clip, args.glances)
        moving.append((load(spec, build, own), noise))
    clips = [load(s, build) for s in specs]
    grid = [("raw", "-", lambda: _Identity())] + evaluate.settings_grid()
    rows, started = [], time.time()
    rows_by_clip = {}
    for k, clip in enumerate(clips + [c for c, _ in moving]):
        per = {}
        for setting in grid:
            roll = filter_output(build, clip, work, setting)
            row = {"clip": clip.name, "source": clip.source, "kind": clip.kind, "filter": setting[0],
                   "setting": setting[1], **clip_metrics(clip, roll)}
            rows.append(row)
            per[(setting[0], setting[1])] = row
        rows_by_clip[clip.name] = per
        log(f"{k + 1}/{len(clips) + len(moving)} clips through {len(grid)} filter settings "
            f"({time.time() - started:.0f} s)")
    with open(os.path.join(out, "truth", "truth_sweep.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    text = report([r for r in rows if r["kind"] == "still frame"], clips)
    held_names = {c.name for c in clips if c.source not in evaluate.TUNING_CLIPS}
    tuned_names = {c.name for c in clips if c.source in evaluate.TUNING_CLIPS}
    groups = [(label, pool([r for r in rows if r["clip"] in names]))
              for label, names in (("tuning clips", tuned_names), ("held out", held_names)) if names]
    text += "\n" + frontier_report(groups)
    plot_frontier(groups, os.path.join(out, "truth", "truth_frontier.png"))
    held = [c for c in clips if c.source not in evaluate.TUNING_CLIPS] or clips
    pooled = pool([r for r in rows if r["clip"] in {c.name for c in held}])
    defaults = next(p for p in pooled if p["filter"] == evaluate.DEFAULTS_NAME)
    euro = at_equal_jitter(pooled, defaults["jitter"]).get("1 euro")
    if moving:
        chosen = [(evaluate.DEFAULTS_NAME, (evaluate.DEFAULTS_NAME, "as shipped"))]
        if euro is not None:
            chosen.append((f"1 euro ({euro['setting']})", ("1 euro", euro["setting"])))
        text += "\n" + moving_report(moving, rows_by_clip, chosen)
    with open(os.path.join(out, "truth", "truth.md"), "w") as f:
        f.write(text)
    print(text)
    if held and euro is not None:
        clip = held[0]
        grid_by = {(s[0], s[1]): s for s in grid}
        outputs = [("hkf defaults", filter_output(build, clip, work, grid_by[(evaluate.DEFAULTS_NAME, "as shipped")])),
                   (f"1 euro ({euro['setting']})", filter_output(build, clip, work, grid_by[("1 euro", euro["setting"])]))]
        plot(clip, outputs, os.path.join(out, "truth", "truth_roll.png"))
        log(f"figure: {os.path.join(out, 'truth', 'truth_roll.png')}")


class _Identity:
    """The raw measurements as a 'filter', for the same metrics."""

    def filter(self, t, z):
        return np.asarray(z, dtype=float)


if __name__ == "__main__":
    main()
