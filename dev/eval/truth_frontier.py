#!/usr/bin/env python3
"""The frontier on the project's own truth: moving error against still jitter, per axis, frame rate and
second-model timing, for the defaults and the motion adaptation's knobs swept around them.

Truth: roll from truth_eval.py's clips (real faces turned in the image plane along driver trajectories; the
mesh alone, as frontal faces take it), yaw and pitch from turn_truth.py's (textured 3D heads turned along held
turns; both models). Each at 30 and 60 fps (the 60 fps clips made at that rate: roll from the most frontal
frame of each clip, yaw and pitch every head). Yaw and pitch with two timings of the second model (WHENet):
- on time: each WHENet measurement 12 ms after the mesh's (a fast CPU; turn_truth's "fast CPU" order);
- the slowest level: the estimator run again on the same frames with its layers and OpenCV's at sse2
  (dev/slower_machine.sh --level sse2 on every core), each measurement as late as it came there.
Then hkf-filter --offline with each setting of GRID (start_rate x stop_rate, the defaults' q). Per (axis, rate,
timing, setting), pooled over the tuning clips and the held-out ones (evaluate.TUNING_CLIPS):
- moving error: RMSE where the truth moves faster than 10 deg/s, each frame's newest pose, over raw's;
- still jitter: the published stream's steps over every settled hold against raw's, pooled, and the worst hold;
- the largest reversal within a move.
The frontier: the least moving error a setting reaches at a pooled still jitter of at most each share of raw's.
And where the defaults' excess moving error is, by segment of the trajectory and by place in a move.

usage: truth_frontier.py [--build DIR] [--out DIR] [--rates 30,60]
writes OUT/frontier/{frontier.md,frontier_rows.csv,truth_frontier_axes.png}; the clips under OUT/truth*, OUT/turn* (made once, reused).
"""
import argparse
import csv
import os
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import evaluate  # noqa: E402
import truth_eval  # noqa: E402
import turn_truth  # noqa: E402

START_RATES = [0.002, 0.01, 0.05, 0.3, 2.0, 8.0]  # 1/s: the defaults' 0.05, widened both ways until the best sat inside
STOP_RATES = [0.25, 1.0, 4.0, 16.0, 64.0, 256.0]  # 1/s: the defaults' 16, by factors of 4, widened the same way
GRID = [("defaults", ())] + [(f"start_rate {a:g}, stop_rate {b:g}", (f"start_rate={a:g}", f"stop_rate={b:g}"))
                             for a in START_RATES for b in STOP_RATES]
SHARES = [0.05, 0.10, 0.20]      # still jitter as a share of raw's
GOALS = {"moving_ratio": 1.0, "jitter_share": 0.10, "reversal_deg": 0.3}


def log(message):
    print(f"truth_frontier: {message}", flush=True)


class RollClip:
    """A truth_eval clip in turn_truth's shape (axis, truth per axis, raw per frame, frame index), so that
    turn_truth's measures (holds, moving_error, largest_reversal) take it."""

    def __init__(self, clip):
        self.name, self.role = clip.name, "tuning" if clip.source in evaluate.TUNING_CLIPS else "held out"
        self.axis, self.axis_name = truth_eval.ROLL, "roll"
        self.trajectory, self.log, self.t, self.utime = clip.trajectory, clip.log, clip.t, clip.utime
        self.theta = clip.trajectory.theta[:len(clip.t)]
        self.truth = np.full((len(clip.t), 3), np.nan)
        self.truth[:, self.axis] = clip.truth
        self.moving = clip.moving & np.isfinite(clip.truth)
        self.z = np.where(clip.valid[:, None], clip.z, np.nan)
        self.index = {int(u): i for i, u in enumerate(self.utime)}

    def raw_taken(self):
        return self.z


def roll_clips(build, out, fps):
    """truth_eval's clips at fps: at 30 fps its own (two faces a clip), at another rate the most frontal one."""
    truth_eval.FPS = fps
    folder = out if fps == 30 else os.path.join(out, f"truth{fps:g}fps")
    os.makedirs(os.path.join(folder, "truth", "clips"), exist_ok=True)
    specs = []
    for clip in [c for c in evaluate.clips() if "shared" in c]:
        specs += truth_eval.make_still_clips(build, folder, clip, 2 if fps == 30 else 1, 4)
    return [RollClip(truth_eval.load(s, build)) for s in specs]


def turn_clips(build, out, fps):
    turn_truth.FPS = fps
    folder = out if fps == 30 else os.path.join(out, f"turn{fps:g}fps")
    os.makedirs(os.path.join(folder, "turn"), exist_ok=True)
    return turn_truth.make_clips(build, folder, turn_truth.HEADS)[0]


def sse2_log(build, log_path, fps):
    """The estimator again on the clip's frames with every layer at sse2 (dev/slower_machine.sh), made once."""
    path = log_path.replace(".lcmlog", ".sse2.lcmlog")
    if not os.path.exists(path):
        started = time.time()
        cores = f"0-{os.cpu_count() - 1}"
        command = [os.path.join(evaluate.ROOT, "dev", "slower_machine.sh"), "--level", "sse2", "--core", cores,
                   "--load", "0", os.path.join(build, "estimator", "hkf-estimator"),
                   "--source", log_path[:-len(".lcmlog")], "--fps", f"{fps:g}", "--lcm-url", f"file://{path}.part?mode=w"]
        result = subprocess.run(command, capture_output=True, text=True)
        if result.returncode != 0:
            evaluate.fail(f"{' '.join(command)} exited {result.returncode}: {result.stderr.strip()[-400:]}")
        said = [line for line in (result.stdout + result.stderr).splitlines() if "capture->publish" in line]
        log(f"{os.path.basename(path)}: {time.time() - started:.0f} s; " + "; ".join(said))
        os.replace(path + ".part", path)
    return path


def timings(clip, build, fps):
    """(timing, the clip as that log has it, the raw log as a camera delivers it): roll has one model, yaw and
    pitch two; at sse2 the estimator's own run, its measurements and their lateness."""
    types_dir = os.path.join(build, "lcmtypes", "python")
    if clip.axis_name == "roll":
        return [("mesh alone", clip, clip.log)]
    slow_log = sse2_log(build, clip.log, fps)
    slow = turn_truth.TurnClip(clip.head, clip.axis_name, clip.trajectory, slow_log,
                               turn_truth.read_measurements(slow_log, types_dir)[0])
    return [("WHENet on time", clip, turn_truth.retimed(clip.log, types_dir, turn_truth.FAST_LATE_US)),
            ("WHENet at sse2", slow, turn_truth.retimed(slow_log, types_dir, None))]


def measure(clip, rows):
    """One clip's figures for one run: squared errors and counts, hold jitter, reversal, per-frame output."""
    a = clip.axis
    newest, raw = turn_truth.newest_per_frame(clip, rows)[:, a], clip.raw_taken()[:, a]
    ok = clip.moving & np.isfinite(newest) & np.isfinite(raw)
    truth = clip.truth[:, a]
    holds = turn_truth.holds(clip, rows)
    return {"se": float(np.sum((newest[ok] - truth[ok]) ** 2)), "se_raw": float(np.sum((raw[ok] - truth[ok]) ** 2)),
            "n": int(ok.sum()), "holds": holds, "reversal": turn_truth.largest_reversal(clip, rows),
            "error": newest - truth, "raw_error": raw - truth, "ok": ok}


def pooled(runs):
    """Moving error over raw's, the still jitter's pooled share and worst hold share, the largest reversal."""
    se, se_raw, n = (sum(r[k] for r in runs) for k in ("se", "se_raw", "n"))
    holds = [h for r in runs for h in r["holds"]]
    steps = sum(c - 1 for _, _, _, c in holds)
    published = sum(p * p * (c - 1) for _, p, _, c in holds)
    raw = sum(r * r * (c - 1) for _, _, r, c in holds)  # raw's steps weighted as the published ones'
    share = np.sqrt(published / raw) if steps and raw > 0 else np.nan
    worst = max((p / r for _, p, r, _ in holds if r > 0), default=np.nan)
    return {"ratio": np.sqrt(se / se_raw) if se_raw > 0 else np.nan, "share": share, "worst": worst,
            "reversal": max(r["reversal"] for r in runs), "clips": len(runs), "moving": n}


def places(clip):
    """Per frame: 0, 1, 2 for the first two frames of a moving stretch, its middle, its last two; -1 still."""
    place = np.full(len(clip.moving), -1)
    edges = np.flatnonzero(np.diff(np.concatenate(([0], clip.moving.astype(int), [0]))))
    for start, stop in zip(edges[::2], edges[1::2]):
        k = np.arange(start, stop)
        place[k] = np.where(k - start < 2, 0, np.where(stop - k <= 2, 2, 1))
    return place


def segments(clip):
    """Per frame: the trajectory's segment name (a glance, a sine, ...)."""
    names = np.array([""] * len(clip.t), dtype=object)
    for name, t0, t1 in clip.trajectory.segments:
        names[(clip.t >= t0) & (clip.t < t1)] = name
    return names


def where_the_error_is(pairs):
    """pairs: (clip, defaults' run). RMSE of the defaults and of raw on moving frames by place in the move
    and by segment: {label: (defaults, raw, frames)}."""
    sums = {}
    for clip, run in pairs:
        keys = [("place", ("first two frames", "middle", "last two frames")[p]) if p >= 0 else None
                for p in places(clip)]
        for label, key in (("place", keys), ("segment", [("segment", n) for n in segments(clip)])):
            for i in np.flatnonzero(run["ok"]):
                if key[i] is None:
                    continue
                total = sums.setdefault(key[i], [0.0, 0.0, 0])
                total[0] += run["error"][i] ** 2
                total[1] += run["raw_error"][i] ** 2
                total[2] += 1
    return {key: (np.sqrt(a / n), np.sqrt(b / n), n) for key, (a, b, n) in sums.items() if n}


def run_all(build, out, rates):
    """results[(axis, fps, timing, role, setting)] = runs; defaults[(axis, fps, timing)] = (clip, run) held out."""
    program = os.path.join(build, "tools", "hkf-filter")
    results, defaults, started = {}, {}, time.time()
    for fps in rates:
        clips = roll_clips(build, out, fps) + turn_clips(build, out, fps)
        for k, clip in enumerate(clips):
            for timing, timed, log_path in timings(clip, build, fps):
                for label, settings in GRID:
                    work = os.path.join(out, "frontier", "work")
                    run = measure(timed, turn_truth.published(program, log_path, work, settings))
                    results.setdefault((clip.axis_name, fps, timing, clip.role, label), []).append(run)
                    if label == "defaults" and clip.role == "held out":
                        defaults.setdefault((clip.axis_name, fps, timing), []).append((timed, run))
            log(f"{fps:g} fps: {k + 1}/{len(clips)} clips through {len(GRID)} settings ({time.time() - started:.0f} s)")
    return results, defaults


def percent(x):
    return f"{100 * x:.0f} %" if np.isfinite(x) else "-"


def defaults_table(summary):
    lines = ["| axis | rate | second model | clips | moving error (x raw's) | still jitter: pooled, worst hold "
             "(of raw's) | largest reversal (deg) |", "| --- | ---: | --- | --- | ---: | --- | ---: |"]
    for (axis, fps, timing, role, label), s in sorted(summary.items()):
        if label == "defaults":
            lines.append(f"| {axis} | {fps:g} fps | {timing} | {role} ({s['clips']}) | {s['ratio']:.2f} | "
                         f"{percent(s['share'])}, {percent(s['worst'])} | {s['reversal']:.2f} |")
    return lines


def frontier_table(summary):
    lines = ["| axis | rate | second model | clips | " + " | ".join(f"<= {100 * x:.0f} %" for x in SHARES) + " |",
             "| --- | ---: | --- | --- |" + " --- |" * len(SHARES)]
    keys = sorted({k[:4] for k in summary})
    for axis, fps, timing, role in keys:
        cells = []
        for share in SHARES:
            inside = [(s["ratio"], label) for (a, f, t, r, label), s in summary.items()
                      if (a, f, t, r) == (axis, fps, timing, role) and s["share"] <= share]
            best = min(inside, default=None)
            cells.append(f"{best[0]:.2f} ({best[1]})" if best else "-")
        lines.append(f"| {axis} | {fps:g} fps | {timing} | {role} | " + " | ".join(cells) + " |")
    return lines


def error_table(defaults):
    """Where the defaults' moving error is, held out: by place in a move and by segment."""
    lines = ["| axis | rate | second model | " + "first two frames | middle | last two frames | "
             "by segment: the defaults (raw), frames |", "| --- | ---: | --- | --- | --- | --- | --- |"]
    for (axis, fps, timing), pairs in sorted(defaults.items()):
        found = where_the_error_is(pairs)
        cell = [f"{found[('place', p)][0]:.2f} ({found[('place', p)][1]:.2f})" if ("place", p) in found else "-"
                for p in ("first two frames", "middle", "last two frames")]
        parts = ", ".join(f"{key[1]} {v[0]:.2f} ({v[1]:.2f}), {v[2]}" for key, v in sorted(found.items())
                          if key[0] == "segment")
        lines.append(f"| {axis} | {fps:g} fps | {timing} | " + " | ".join(cell) + f" | {parts} |")
    return lines


def goal_lines(summary):
    """The defaults on the held-out clips against the truth goals."""
    lines = []
    for (axis, fps, timing, role, label), s in sorted(summary.items()):
        if label != "defaults" or role != "held out":
            continue
        met = [s["ratio"] <= GOALS["moving_ratio"], s["worst"] <= GOALS["jitter_share"],
               s["reversal"] <= GOALS["reversal_deg"]]
        lines.append(f"- {axis}, {fps:g} fps, {timing}: moving error {s['ratio']:.2f}x raw's "
                     f"({'met' if met[0] else 'NOT met'}: <= {GOALS['moving_ratio']:.1f}x), worst hold "
                     f"{percent(s['worst'])} ({'met' if met[1] else 'NOT met'}: <= "
                     f"{percent(GOALS['jitter_share'])}), reversal {s['reversal']:.2f} deg "
                     f"({'met' if met[2] else 'NOT met'}: <= {GOALS['reversal_deg']:g})")
    return lines


def write_rows(summary, path):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["axis", "fps", "timing", "role", "setting", "clips", "moving_frames", "moving_ratio",
                    "jitter_share", "worst_hold_share", "reversal_deg"])
        for (axis, fps, timing, role, label), s in sorted(summary.items()):
            w.writerow([axis, f"{fps:g}", timing, role, label, s["clips"], s["moving"], f"{s['ratio']:.4f}",
                        f"{s['share']:.4f}", f"{s['worst']:.4f}", f"{s['reversal']:.3f}"])


def figure(summary, path):
    """Per axis, held out: every setting's moving error against its still jitter, one colour per rate and timing,
    the defaults ringed."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker
    axes_names = ["roll", "yaw", "pitch"]
    fig, panels = plt.subplots(1, 3, figsize=(13, 4.2))
    styles = {}
    for panel, axis in zip(panels, axes_names):
        groups = sorted({(f, t) for (a, f, t, r, _) in summary if a == axis and r == "held out"})
        for fps, timing in groups:
            key = f"{fps:g} fps, {timing}"
            colour = styles.setdefault(key, f"C{len(styles)}")
            points = [(s["share"], s["ratio"], label) for (a, f, t, r, label), s in summary.items()
                      if (a, f, t, r) == (axis, fps, timing, "held out") and np.isfinite(s["share"])]
            panel.scatter([100 * p[0] for p in points], [p[1] for p in points], s=14, color=colour, label=key)
            panel.scatter([100 * p[0] for p in points if p[2] == "defaults"],
                          [p[1] for p in points if p[2] == "defaults"], s=90, facecolors="none", edgecolors=colour)
        panel.axvline(100 * GOALS["jitter_share"], color="grey", lw=0.8, ls=":")
        panel.axhline(GOALS["moving_ratio"], color="grey", lw=0.8, ls=":")
        panel.set_xscale("log")
        panel.xaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        panel.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        panel.set_title(f"{axis} (held out)")
        panel.set_xlabel("still jitter over the holds (% of raw's)")
        panel.set_ylabel("moving error (x raw's)")
        panel.legend(fontsize=7)
    fig.suptitle("The frontier on the truth: start_rate x stop_rate swept, the defaults ringed; goal corner at the "
                 "dotted lines")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(evaluate.ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(evaluate.ROOT, "out", "eval"))
    parser.add_argument("--rates", default="30,60", help="frame rates (fps), comma-separated")
    args = parser.parse_args()
    build, out = os.path.abspath(args.build), os.path.abspath(args.out)
    folder = os.path.join(out, "frontier")
    os.makedirs(os.path.join(folder, "work"), exist_ok=True)
    results, defaults = run_all(build, out, [float(r) for r in args.rates.split(",")])
    summary = {key: pooled(runs) for key, runs in results.items()}
    write_rows(summary, os.path.join(folder, "frontier_rows.csv"))
    figure(summary, os.path.join(folder, "truth_frontier_axes.png"))
    lines = ["# The frontier on the project's own truth", "",
             "Made by `./run eval` (dev/eval/truth_frontier.py): roll, yaw and pitch truth at each rate, the second "
             "model on time and at the slowest level's timing, hkf-filter --offline with the defaults and "
             f"start_rate x stop_rate swept ({len(GRID) - 1} settings). Still jitter: the published steps over every "
             "settled hold against raw's.", "", "## The defaults", ""] + defaults_table(summary)
    lines += ["", "## The frontier: the least moving error (x raw's) at a still jitter of at most each share of "
                  "raw's, and the setting that reaches it", ""] + frontier_table(summary)
    lines += ["", "## Where the defaults' moving error is (held out; RMSE in degrees, raw's in brackets)", ""]
    lines += error_table(defaults) + ["", "## Goals: the defaults on the held-out clips", ""] + goal_lines(summary)
    text = "\n".join(lines) + "\n"
    with open(os.path.join(folder, "frontier.md"), "w") as f:
        f.write(text)
    print(text)
    log(f"wrote {folder}/frontier.md and frontier_rows.csv")


if __name__ == "__main__":
    main()
