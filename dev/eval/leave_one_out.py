#!/usr/bin/env python3
"""Leave-one-clip-out tuning of hkf's calibrated filter against the 1 euro filter
and Accela, and the defaults' robustness to a noisier camera.

For each clip in turn: hkf's setting is chosen on all the other clips (the rule
below), then measured on the left-out clip; the 1 euro filter and Accela are
swept on the left-out clip itself (their best setting there: a fair sweep, and
an advantage to them). The worst left-out clip decides.

The choosing rule, on the tuning clips: among the settings whose still jitter is
at most TUNING_SHARE of raw on every judged tuning clip (a margin below the goal,
SHARE_GOAL), the one with the lowest
worst lag ratio (hkf's lag over the 1 euro filter's at hkf's jitter, on the 1
euro front of that clip). A clip is judged where it has enough frames for both
figures (MIN_STILL_PAIRS still pairs, MIN_MOVING moving frames); the others are
still run and listed.

Noise robustness: the defaults as shipped on each judged clip with white noise
added, so that the frame noise is x1.5 and x2 of the clip's own (its still
frames' RMS residual from the reference): the still jitter as a share of raw,
and its change.

The jitter-lag frontier on each judged clip: the least lag hkf's grid and the 1 euro sweep reach at a still
jitter of at most 5-30 % of raw's (frontier.md, real_frontier.png).

usage: leave_one_out.py [--build DIR] [--out DIR]
writes OUT/loo/{loo.md, noise.md, frontier.md, loo_sweep.csv, loo.png, real_frontier.png} and prints the tables.
"""
import argparse
import csv
import itertools
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import evaluate  # noqa: E402
import metrics  # noqa: E402
import peer_filters  # noqa: E402

ROOT = evaluate.ROOT
ESTIMATOR = "mesh_pnp"  # the default estimator
SHARE_GOAL = 0.25       # still jitter at most this share of raw
TUNING_SHARE = 0.20     # chosen with a margin: at most this share on every tuning clip (see choose)
LAG_GOAL = 0.70         # lag at most this share of the best 1 euro's at equal jitter
NOISE_GOAL = 0.20       # the share changes by at most this with x1.5 and x2 noise
MIN_STILL_PAIRS = 25
MIN_MOVING = 40
NOISE_FACTORS = [1.0, 1.5, 2.0]
# hkf with noise calibration and the motion adaptation: every combination is one setting
CALIBRATED = {  # widened four times (docs/evaluation.md): stop_rate and q's floor keep walking to their edge
    "process_noise": [60, 250, 1000, 4000, 16000],  # deg^2/s^3: MOVE's q (16384 is fixed point's limit)
    "start_rate": [0.002, 0.01, 0.05, 0.3],  # 1/s: how often a still head starts to move
    "stop_rate": [0.25, 1, 4],               # 1/s: how often a moving head stops
    "still_wander": [0, 0.03, 0.1, 0.3, 0.5, 1.0, 2.0],  # deg^2: HOLD's R + this
    "loop_closure": ["off", "norm"],
    "noise_rise": [0, 0.01, 0.05, 0.2],      # 1/s: how fast the measured noise n may rise (0: never)
}
CALIBRATED_FIXED = ["noise_time=0.3", "noise_mode=adaptive"]
# the paper's filter (hkf_paper_settings), for comparison
PAPER = ["noise_time=0", "process_noise=500 1000 500", "start_rate=0", "loop_closure=norm", "noise_mode=adaptive"]
ONE_EURO_MIN_CUTOFF = [0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0, 1.5, 2.0, 3.0, 5.0]
ONE_EURO_BETA = [0.0, 0.001, 0.003, 0.01, 0.03, 0.1, 0.2, 0.3, 0.5, 1.0, 2.0, 3.0]
ACCELA_SMOOTHING = evaluate.ACCELA_SMOOTHING


def log(message):
    print(f"leave_one_out: {message}", flush=True)


def calibrated_grid():
    keys = list(CALIBRATED)
    grid = []
    for values in itertools.product(*(CALIBRATED[k] for k in keys)):
        options = list(CALIBRATED_FIXED)
        label = []
        for k, v in zip(keys, values):
            options.append(f"{k}={v} {v} {v}" if k == "process_noise" else f"{k}={v}")
            label.append(f"{k} {v}")
        grid.append((", ".join(label), options))
    return grid


def hkf_output(build, raw, work, utime, options):
    posteriors = evaluate.run_hkf(build, raw, work, options)
    return np.array([posteriors.get(int(u), (np.nan,) * 3) for u in utime])


def clip_noise(t, valid, z):
    """The clip's frame noise per axis: RMS residual from the reference over still frames (deg)."""
    tv, zv = t[valid], z[valid]
    ref = metrics.reference(tv, zv)
    still, _ = metrics.masks(tv, ref)
    residual = metrics.unwrap_yaw(zv) - ref
    return np.sqrt(np.mean(residual[still] ** 2, axis=0)) if still.sum() >= 10 else None


def write_noisy_log(source, path, types_dir, extra_sigma, seed):
    """A copy of the raw log's HEAD_POSE_RAW messages with white noise of extra_sigma (deg, per axis) added."""
    import lcm
    sys.path.insert(0, types_dir)
    from hkf import head_pose_measurement_t
    rng = np.random.default_rng(seed)
    out = lcm.EventLog(path, "w", overwrite=True)
    for event in lcm.EventLog(source, "r"):
        if event.channel != "HEAD_POSE_RAW":
            continue
        m = head_pose_measurement_t.decode(event.data)
        if m.valid:
            noise = rng.normal(0.0, 1.0, 3) * extra_sigma
            m.pitch, m.yaw, m.roll = m.pitch + noise[0], m.yaw + noise[1], m.roll + noise[2]
        out.write_event(event.timestamp, event.channel, m.encode())
    out.close()


def peer_points(t, valid, z):
    """(1 euro points, Accela points) on one clip: dicts with jitter, lag_ms, setting."""
    euro, accela = [], []
    for mc, beta in itertools.product(ONE_EURO_MIN_CUTOFF, ONE_EURO_BETA):
        m = evaluate.measure(t, valid, z, peer_filters.run(peer_filters.OneEuro(mc, beta), t, z, valid))
        euro.append(dict(m, setting=f"min_cutoff {mc:g} Hz, beta {beta:g}"))
    for s in ACCELA_SMOOTHING:
        m = evaluate.measure(t, valid, z, peer_filters.run(peer_filters.Accela(s), t, z, valid,
                                                           peer_filters.OPENTRACK_TICK_S))
        accela.append(dict(m, setting=f"smoothing {s:g}"))
    return [p for p in euro if not np.isnan(p["jitter"])], [p for p in accela if not np.isnan(p["jitter"])]


def real_clip(build, out, types, path):
    """A real clip through the default estimator: (name, its raw log, the measurements' utime, the clip: t, valid,
    z, raw's metrics and the 1 euro sweep's points, as ratios() wants it)."""
    name = os.path.splitext(os.path.basename(path))[0]
    raw = evaluate.raw_log(build, out, path, ESTIMATOR)
    utime, t, valid, z = evaluate.read_raw(raw, types)
    clip = {"t": t, "valid": valid, "z": z, "raw": evaluate.measure(t, valid, z, np.where(valid[:, None], z, np.nan))}
    clip["euro"], _ = peer_points(t, valid, z)
    return name, raw, utime, clip


def judged(clip):
    return clip["raw"]["still_pairs"] >= MIN_STILL_PAIRS and clip["raw"]["moving"] >= MIN_MOVING


def ratios(clip, m):
    """(share of raw jitter, lag over the 1 euro's at this jitter, the 1 euro lag) of one hkf result. Stiller
    than any 1 euro setting: against the 1 euro's stillest (which has more jitter); jitterier than all: no ratio."""
    lag1, _ = evaluate.lag_at(clip["euro"], m["jitter"])
    front = evaluate.front(clip["euro"])
    if lag1 is None and front and m["jitter"] < front[0]["jitter"]:
        lag1 = front[0]["lag_ms"]
    share = m["jitter"] / clip["raw"]["jitter"]
    return share, (m["lag_ms"] / lag1 if lag1 else float("inf")), lag1


def choose(clips, names, grid_size):
    """The setting index chosen on these clips (the rule in the module's text). The share is held to
    TUNING_SHARE, not SHARE_GOAL, on the tuning clips: a setting at the goal's very limit there lands beyond
    it on a new clip (measured: chosen at <= 25 % on three clips, 25 % on d14, and 1.13x its 1 euro lag)."""
    best, best_key = None, None
    for k in range(grid_size):
        shares, lags = [], []
        for name in names:
            share, ratio, _ = ratios(clips[name], clips[name]["hkf"][k])
            shares.append(share)
            lags.append(ratio)
        key = (max(shares) > TUNING_SHARE, max(lags) if max(shares) <= TUNING_SHARE else max(shares))
        if best_key is None or key < best_key:
            best, best_key = k, key
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(ROOT, "out", "eval"))
    parser.add_argument("--baseline", metavar="BUILD",
                        help="another build (e.g. of the last release) whose hkf-filter defaults are compared per clip")
    args = parser.parse_args()
    build, out = os.path.abspath(args.build), os.path.abspath(args.out)
    types = os.path.join(build, "lcmtypes", "python")
    if not os.path.exists(os.path.join(build, "tools", "hkf-filter")):
        evaluate.fail(f"no {build}/tools/hkf-filter: build first (./run build)")
    folder = os.path.join(out, "loo")
    work = os.path.join(folder, "work")
    os.makedirs(work, exist_ok=True)
    grid = calibrated_grid()
    baseline = os.path.abspath(args.baseline) if args.baseline else None
    if baseline and not os.path.exists(os.path.join(baseline, "tools", "hkf-filter")):
        evaluate.fail(f"no {baseline}/tools/hkf-filter: build the baseline first")
    clips = measure_all(build, out, types, work, grid, baseline)
    report(clips, grid, folder, build, types, work)
    if baseline:
        baseline_report(clips, baseline, folder)


def measure_all(build, out, types, work, grid, baseline=None):
    """Per clip: its raw log and poses, the raw, hkf (every grid setting and the defaults), 1 euro and Accela metrics."""
    clips = {}
    for path in evaluate.clips():
        started = time.time()
        raw = evaluate.raw_log(build, out, path, ESTIMATOR)
        utime, t, valid, z = evaluate.read_raw(raw, types)
        name = os.path.splitext(os.path.basename(path))[0]
        clip = {"raw_log": raw, "utime": utime, "t": t, "valid": valid, "z": z,
                "raw": evaluate.measure(t, valid, z, np.where(valid[:, None], z, np.nan))}
        clip["euro"], clip["accela"] = peer_points(t, valid, z)
        clip["hkf"] = [evaluate.measure(t, valid, z, hkf_output(build, raw, work, utime, options))
                       for _, options in grid]
        clip["defaults"] = evaluate.measure(t, valid, z, hkf_output(build, raw, work, utime, []))
        if baseline:
            clip["baseline"] = evaluate.measure(t, valid, z, hkf_output(baseline, raw, work, utime, []))
        clips[name] = clip
        log(f"{name}: {len(grid)} hkf settings, {len(clip['euro'])} 1 euro, {len(clip['accela'])} Accela "
            f"({time.time() - started:.0f} s)")
    return clips


def report(clips, grid, folder, build, types, work):
    """The leave-one-out and noise tables (printed and written to folder) and the figure."""
    with open(os.path.join(folder, "loo_sweep.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["clip", "setting", "jitter", "lag_ms", "raw_jitter", "still_pairs", "moving"])
        for name, clip in clips.items():
            for (label, _), m in zip(grid, clip["hkf"]):
                w.writerow([name, label, f"{m['jitter']:.5f}", f"{m['lag_ms']:.1f}", f"{clip['raw']['jitter']:.5f}",
                            clip["raw"]["still_pairs"], clip["raw"]["moving"]])

    names = [n for n in clips if judged(clips[n])]
    lines = [f"Leave one clip out ({ESTIMATOR}; {len(clips)} clips, judged where a clip has >= {MIN_STILL_PAIRS} "
             f"still pairs and >= {MIN_MOVING} moving frames: {', '.join(names)}). hkf's setting is chosen on the "
             f"other judged clips; the 1 euro filter and Accela are swept on the left-out clip itself.\n",
             "| left-out clip | raw still jitter | hkf (chosen without it): jitter, share of raw | hkf lag | "
             "1 euro lag at hkf's jitter | hkf / 1 euro | Accela lag at hkf's jitter | hkf setting chosen |",
             "| --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |"]
    worst_ratio, worst_share, loo_points = 0.0, 0.0, {}
    for name in names:
        k = choose(clips, [n for n in names if n != name], len(grid))
        c = clips[name]
        m = c["hkf"][k]
        share, ratio, lag1 = ratios(c, m)
        lag_a, _ = evaluate.lag_at(c["accela"], m["jitter"])
        worst_ratio, worst_share = max(worst_ratio, ratio), max(worst_share, share)
        loo_points[name] = m
        lines.append(f"| {name} | {c['raw']['jitter']:.3f} deg | {m['jitter']:.3f} deg, {100 * share:.0f} % | "
                     f"{m['lag_ms']:.0f} ms | {'%.0f ms' % lag1 if lag1 else '(not reached)'} | {ratio:.2f} | "
                     f"{'%.0f ms' % lag_a if lag_a is not None else '(not reached)'} | {grid[k][0]} |")
    lines.append(f"\nWorst left-out clip: lag {worst_ratio:.2f}x the best 1 euro at equal jitter (goal <= "
                 f"{LAG_GOAL:.2f}: {'met' if worst_ratio <= LAG_GOAL else 'NOT met'}); still jitter "
                 f"{100 * worst_share:.0f} % of raw (goal <= {100 * SHARE_GOAL:.0f} %: "
                 f"{'met' if worst_share <= SHARE_GOAL else 'NOT met'}).")
    k_all = choose(clips, names, len(grid))
    lines.append(f"\nChosen on all judged clips (the shipped defaults should be this): {grid[k_all][0]}.")
    lines.append("\nThe defaults as shipped, per clip (every clip; judged ones against the goals):\n")
    lines.append("| clip | still pairs | moving frames | raw jitter | defaults: jitter, share | lag | "
                 "1 euro lag at that jitter | ratio |")
    lines.append("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for name, c in clips.items():
        m = c["defaults"]
        if np.isnan(c["raw"]["jitter"]) or np.isnan(m["jitter"]):
            lines.append(f"| {name} | {c['raw']['still_pairs']} | {c['raw']['moving']} | (no still frames) | | "
                         f"{m['lag_ms']:.0f} ms | | |")
            continue
        share, ratio, lag1 = ratios(c, m)
        lines.append(f"| {name} | {c['raw']['still_pairs']} | {c['raw']['moving']} | {c['raw']['jitter']:.3f} deg | "
                     f"{m['jitter']:.3f} deg, {100 * share:.0f} % | {m['lag_ms']:.0f} ms | "
                     f"{'%.0f ms' % lag1 if lag1 else '(not reached)'} | "
                     f"{'%.2f' % ratio if lag1 else ''}{'' if name in names else ' (not judged)'} |")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(folder, "loo.md"), "w") as f:
        f.write(text)
    print(text)

    noise_lines = ["Noise robustness: white noise added to the raw poses (frame noise x1.5 and x2 of the clip's "
                   "own); still jitter as a share of raw, and its largest change from x1.\n",
                   "| settings | clip | x1 | x1.5 | x2 | largest change |", "| --- | --- | ---: | ---: | ---: | ---: |"]
    compared = (("defaults as shipped", []), ("the paper's filter", PAPER))
    shares = {label: {name: [] for name in names} for label, _ in compared}
    for i, name in enumerate(names):  # each noisy log made once, every setting run on it
        c = clips[name]
        sigma = clip_noise(c["t"], c["valid"], c["z"])
        for factor in NOISE_FACTORS:
            path = os.path.join(work, f"{name}.noise{factor:g}.lcmlog")
            write_noisy_log(c["raw_log"], path, types, sigma * np.sqrt(factor ** 2 - 1.0), seed=i)
            _, t, valid, z = evaluate.read_raw(path, types)
            raw = evaluate.measure(t, valid, z, np.where(valid[:, None], z, np.nan))
            for label, options in compared:
                mine = evaluate.measure(t, valid, z, hkf_output(build, path, work, c["utime"], options))
                shares[label][name].append(mine["jitter"] / raw["jitter"])
    for label, _ in compared:
        worst_change = 0.0
        for name in names:
            row = shares[label][name]
            change = max(abs(s / row[0] - 1.0) for s in row[1:])
            worst_change = max(worst_change, change)
            noise_lines.append(f"| {label} | {name} | {100 * row[0]:.0f} % | {100 * row[1]:.0f} % | "
                               f"{100 * row[2]:.0f} % | {100 * change:.0f} % |")
        noise_lines.append(f"| {label} | largest change | | | | {100 * worst_change:.0f} % (goal <= "
                           f"{100 * NOISE_GOAL:.0f} %: {'met' if worst_change <= NOISE_GOAL else 'NOT met'}) |")
    text = "\n".join(noise_lines) + "\n"
    with open(os.path.join(folder, "noise.md"), "w") as f:
        f.write(text)
    print(text)
    plot(clips, names, loo_points, os.path.join(folder, "loo.png"))
    text = frontier_report(clips, names)
    with open(os.path.join(folder, "frontier.md"), "w") as f:
        f.write(text)
    print(text)
    plot_frontier(clips, names, os.path.join(folder, "real_frontier.png"))


FRONTIER_SHARES = [0.05, 0.08, 0.10, 0.15, 0.20, 0.25, 0.30]  # still jitter as a share of raw's (the span)


def best_lag(points, limit):
    """The least lag among settings no more jittery than limit (deg), or nan."""
    fits = [p["lag_ms"] for p in points if p["jitter"] <= limit and np.isfinite(p["lag_ms"])]
    return min(fits) if fits else float("nan")


def frontier_report(clips, names):
    """The jitter-lag frontier on the real clips: per judged clip, the least lag hkf's grid and the 1 euro
    filter's sweep reach at a still jitter of at most each share of raw's, and their ratio (every setting on
    every clip: an in-sample frontier, what the design can reach, not what one default gives)."""
    lines = ["The jitter-lag frontier on the real clips: the least lag (ms) at a still jitter of at most a share of "
             "raw's (hkf: every setting of the leave-one-out grid; 1 euro: its sweep; in-sample on each clip).\n",
             "| clip | filter | " + " | ".join(f"<= {100 * s:g} %" for s in FRONTIER_SHARES) + " |",
             "| --- | --- | " + " | ".join("---:" for _ in FRONTIER_SHARES) + " |"]

    def cell(v, bold=False):
        return "-" if not np.isfinite(v) else (f"**{v:.2f}**" if bold else f"{v:.0f}")
    for name in names:
        c = clips[name]
        limits = [share * c["raw"]["jitter"] for share in FRONTIER_SHARES]
        mine = [best_lag(c["hkf"], x) for x in limits]
        euro = [best_lag(c["euro"], x) for x in limits]
        ratio = [a / b if np.isfinite(a) and np.isfinite(b) and b > 0 else float("nan") for a, b in zip(mine, euro)]
        lines.append(f"| {name} | hkf | " + " | ".join(cell(v) for v in mine) + " |")
        lines.append(f"| {name} | 1 euro | " + " | ".join(cell(v) for v in euro) + " |")
        lines.append(f"| {name} | hkf / 1 euro | " + " | ".join(cell(v, True) for v in ratio) + " |")
    return "\n".join(lines) + "\n"


def plot_frontier(clips, names, path):
    """Per judged clip: still jitter (share of raw's) against lag, hkf's grid and front, the 1 euro filter's
    sweep and front, the defaults and raw."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(names), figsize=(4.2 * len(names), 3.9), squeeze=False)
    for ax, name in zip(axes[0], names):
        c = clips[name]
        raw = c["raw"]["jitter"]
        for points, colour, marker, label in ((c["hkf"], "C3", "o", "hkf"), (c["euro"], "C0", "s", "1 euro")):
            ax.plot([p["jitter"] / raw for p in points], [p["lag_ms"] for p in points], marker, color=colour,
                    alpha=0.15, ms=3)
            f = evaluate.front(points)
            ax.plot([p["jitter"] / raw for p in f], [p["lag_ms"] for p in f], "-" + marker, color=colour, ms=3,
                    label=f"{label} (front)")
        ax.plot([c["defaults"]["jitter"] / raw], [c["defaults"]["lag_ms"]], "*", color="k", ms=13, label="hkf defaults")
        ax.plot([1.0], [0.0], "D", color="0.4", ms=6, label="raw")
        ax.axvspan(FRONTIER_SHARES[0], FRONTIER_SHARES[-1], color="0.9", zorder=0)
        ax.set_xlim(0, 1.05)
        ax.set_ylim(-5, 160)
        ax.set_xlabel("still jitter, share of raw's")
        ax.set_ylabel("lag, ms")
        ax.set_title(name)
        ax.grid(alpha=0.3)
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def baseline_report(clips, baseline, folder):
    """The defaults against another build's defaults on the same raw logs, per clip with still frames."""
    lines = [f"The defaults against {baseline}'s hkf-filter defaults, on the same raw logs:\n",
             "| clip | raw jitter | baseline: jitter, share | baseline lag | defaults: jitter, share | defaults lag |",
             "| --- | ---: | ---: | ---: | ---: | ---: |"]
    for name, c in clips.items():
        if np.isnan(c["raw"]["jitter"]):
            continue
        b, m = c["baseline"], c["defaults"]
        lines.append(f"| {name} | {c['raw']['jitter']:.3f} deg | {b['jitter']:.3f} deg, "
                     f"{100 * b['jitter'] / c['raw']['jitter']:.0f} % | {b['lag_ms']:.0f} ms | {m['jitter']:.3f} deg, "
                     f"{100 * m['jitter'] / c['raw']['jitter']:.0f} % | {m['lag_ms']:.0f} ms |")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(folder, "baseline.md"), "w") as f:
        f.write(text)
    print(text)


def plot(clips, names, loo_points, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(names), figsize=(3.6 * len(names), 3.6), squeeze=False)
    for ax, name in zip(axes[0], names):
        c = clips[name]
        raw = c["raw"]["jitter"]
        for points, colour, label in ((c["euro"], "tab:green", "1 euro (front, swept here)"),
                                      (c["accela"], "tab:orange", "Accela (swept here)")):
            f = evaluate.front(points)
            ax.plot([p["jitter"] / raw for p in f], [p["lag_ms"] for p in f], color=colour, marker=".", label=label)
        m = loo_points[name]
        ax.plot([m["jitter"] / raw], [m["lag_ms"]], "b*", markersize=12, label="hkf, tuned without this clip")
        d = c["defaults"]
        ax.plot([d["jitter"] / raw], [d["lag_ms"]], "kP", markersize=9, label="hkf defaults")
        ax.axvline(SHARE_GOAL, color="k", linestyle=":", linewidth=1)
        ax.set_xlim(0, 0.6)
        ax.set_ylim(0, 150)
        ax.set_title(name, fontsize=9)
        ax.set_xlabel("still jitter / raw")
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("lag on moving frames, ms")
    axes[0][0].legend(fontsize=6)
    fig.suptitle("Leave one clip out: lower left is better (./run eval: dev/eval/leave_one_out.py)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    log(path)


if __name__ == "__main__":
    main()
