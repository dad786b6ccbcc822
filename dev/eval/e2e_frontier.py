#!/usr/bin/env python3
"""The jitter-error frontier end to end (the player's-lag issue): still jitter against the error at arrival,
for hkf with its motion adaptation's knob swept, the 1 euro filter swept, and raw, through the live chain.

hkf: the held-out roll clips of e2e.py (REPORT_CLIPS, 30 fps) played through the real programs: the defaults
(the clip's start-up rest measured, stillness 1), the rest measured with stillness in STILLNESS, and, without a
rest (rest_time 0), once per constant still_wander in WANDERS (release 0.3's 0.3 among them), each run measured
as e2e.py measures a variant (the
datagrams against the truth when they arrive). Raw: each measurement as it reaches the node, from the defaults'
run. The 1 euro filter: run on that same raw stream, each measurement filtered as it arrives (what a 1 euro
filter in the node's place would publish, less its fraction of a millisecond), over evaluate.py's whole grid
(min_cutoff x beta x d_cutoff), widened. Per clip, the least error at arrival each family reaches at a still jitter of at
most each share of raw's (SHARES), and a figure of every point.

usage: e2e_frontier.py [--build DIR] [--out DIR]   (about 8 min; root: a private network namespace, as e2e.py)
writes OUT/frontier.md and OUT/e2e_frontier.png
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import e2e  # noqa: E402
import evaluate  # noqa: E402
import peer_filters  # noqa: E402

WANDERS = [0.0, 0.03, 0.1, 0.3, 1.0]  # deg^2: hkf's still_wander without a rest; 0.03 the built-in, 0.3 release 0.3's
STILLNESS = [0.25, 4.0]                # the player's knob with the rest measured (1: the defaults)
SHARES = [0.05, 0.10, 0.20, 0.30]     # still jitter as a share of raw's (the span)
# the 1 euro grid: evaluate.py's, widened where its best points here sat at its edges (min_cutoff 0.005, d_cutoff 2 Hz)
ONE_EURO_MIN_CUTOFF = [0.0001, 0.0003, 0.001, 0.002] + evaluate.ONE_EURO_MIN_CUTOFF
ONE_EURO_D_CUTOFF = evaluate.ONE_EURO_D_CUTOFF + [4.0, 8.0]


def hkf_variants():
    return ([e2e.Variant("defaults")] + [e2e.Variant(f"stillness {s:g}", (f"stillness={s:g}",)) for s in STILLNESS] +
            [e2e.Variant(f"still_wander {w:g}, no rest", ("rest_time=0", f"still_wander={w:g}")) for w in WANDERS])


def one_euro_points(raw, clip):
    """(setting, measures) of the 1 euro grid run on the raw stream as it arrives (raw: e2e.read_chain_log's)."""
    valid = raw[raw[:, 3] != 0]
    points = []
    for mc in ONE_EURO_MIN_CUTOFF:
        for beta in evaluate.ONE_EURO_BETA:
            for dc in ONE_EURO_D_CUTOFF:
                f = peer_filters.OneEuro(mc, beta, dc)
                rolls = [f.filter(u * 1e-6, (0.0, 0.0, roll))[2] for u, roll in zip(valid[:, 1], valid[:, 4])]
                datagrams = [(t, (0.0, 0.0, 0.0, 0.0, 0.0, -r)) for t, r in zip(valid[:, 0], rolls)]
                m = e2e.measure_run(clip, datagrams, raw, np.zeros((0, 4)), "", e2e.roll_of_datagram,
                                    e2e.roll_truth)
                points.append((f"min_cutoff {mc:g}, beta {beta:g}, d_cutoff {dc:g}", m))
    return points


def best_within(points, raw_jitter, share):
    """The (error at arrival, setting, jitter share) least in error among points within share of raw's jitter."""
    inside = [(m["at_arrival"], name, m["jitter"] / raw_jitter) for name, m in points
              if np.isfinite(m["at_arrival"]) and m["jitter"] <= share * raw_jitter]
    return min(inside) if inside else None


def clip_points(build, out, clip_name):
    """The hkf runs, raw, and the 1 euro grid on one held-out clip."""
    clip = e2e.make_clip(out, e2e.frontal_frame(build, out, clip_name), clip_name, 30.0, "roll", short=False)
    runs = e2e.run_clip(build, out, clip, hkf_variants(), e2e.roll_of_datagram, e2e.roll_truth)
    named = dict(runs)
    raw_jitter = named[e2e.SAME_RUN_RAW]["jitter"]
    work = os.path.join(out, "runs", clip.name, "defaults")
    raw, _ = e2e.read_chain_log(os.path.join(work, "chain.lcmlog"), os.path.join(build, "lcmtypes", "python"))
    hkf = [(name, m) for name, m in runs if name != e2e.SAME_RUN_RAW]
    e2e.log(f"{clip.name}: the 1 euro grid on the raw stream ...")
    return clip, hkf, named[e2e.SAME_RUN_RAW], one_euro_points(raw, clip), raw_jitter


def at_edges(setting):
    """The 1 euro parameters of a setting's name that sit at an edge of the grid."""
    values = dict(part.split(" ") for part in setting.split(", "))
    grids = {"min_cutoff": ONE_EURO_MIN_CUTOFF, "beta": evaluate.ONE_EURO_BETA, "d_cutoff": ONE_EURO_D_CUTOFF}
    return [k for k, grid in grids.items() if float(values[k]) in (min(grid), max(grid))]


def report_lines(clip, hkf, raw_m, euro, raw_jitter):
    lines = [f"## {clip.name} (held out)", "",
             f"Raw (as it reaches the node): error at arrival {raw_m['at_arrival']:.2f} deg, still jitter "
             f"{raw_m['jitter']:.3f} deg, onset median {np.nanmedian(raw_m['onset']):.0f} ms.", "",
             "| hkf | still jitter (of raw) | error at arrival (of raw) | onset median / worst (ms) |",
             "| --- | ---: | ---: | ---: |"]
    for name, m in hkf:
        lines.append(f"| {name} | {100 * m['jitter'] / raw_jitter:.0f} % | {m['at_arrival']:.2f} deg "
                     f"({m['at_arrival'] / raw_m['at_arrival']:.2f}x) | {np.nanmedian(m['onset']):.0f} / "
                     f"{np.nanmax(m['onset']):.0f} |")
    lines += ["", "| still jitter at most | hkf: least error at arrival | 1 euro: least error at arrival | hkf / 1 euro |",
              "| ---: | --- | --- | ---: |"]
    for share in SHARES:
        h, e = best_within(hkf, raw_jitter, share), best_within(euro, raw_jitter, share)
        text = lambda b: "-" if b is None else f"{b[0]:.2f} deg ({b[1]}, {100 * b[2]:.0f} %)"  # noqa: E731
        ratio = f"{h[0] / e[0]:.2f}x" if h and e else "-"
        lines.append(f"| {100 * share:g} % | {text(h)} | {text(e)} | {ratio} |")
    edges = sorted({k for share in SHARES for b in [best_within(euro, raw_jitter, share)] if b for k in at_edges(b[1])})
    lines += ["", "The 1 euro filter's best points sit at the edge of its grid in: " + (", ".join(edges) or "none") + "."]
    return lines + [""]


def plot(path, clips):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(clips), figsize=(6 * len(clips), 4.5), squeeze=False)
    for ax, (clip, hkf, raw_m, euro, raw_jitter) in zip(axes[0], clips):
        ax.scatter([100 * m["jitter"] / raw_jitter for _, m in euro], [m["at_arrival"] for _, m in euro], s=6,
                   color="tab:blue", alpha=0.4, label="1 euro (grid)")
        constant = [(n, m) for n, m in hkf if n.endswith("no rest")]
        rested = [(n, m) for n, m in hkf if not n.endswith("no rest")]
        ax.plot([100 * m["jitter"] / raw_jitter for _, m in constant], [m["at_arrival"] for _, m in constant], "o-",
                color="tab:red", label="hkf, no rest: still_wander 0 - 1")
        ax.plot([100 * m["jitter"] / raw_jitter for _, m in rested], [m["at_arrival"] for _, m in rested], "D",
                color="tab:green", label="hkf, the rest measured (stillness 0.25, 1, 4)")
        for name, m in hkf:
            ax.annotate(name.replace("still_wander ", "w ").replace(", no rest", "").replace("defaults", "rest"),
                        (100 * m["jitter"] / raw_jitter, m["at_arrival"]), fontsize=7, xytext=(3, 3),
                        textcoords="offset points")
        ax.plot([100], [raw_m["at_arrival"]], "ks", label="raw")
        ax.set_xscale("log")
        ax.set_xlim(1, 300)
        ax.set_ylim(0, max(3.0 * raw_m["at_arrival"], 1.0))
        ax.set_xlabel("still jitter, % of raw's (log)")
        ax.set_ylabel("error at arrival on moving frames, deg")
        ax.set_title(clip.name)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=os.path.join(e2e.ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(e2e.ROOT, "out", "e2e"))
    args = parser.parse_args()
    if os.environ.get("HKF_IN_NETNS") != "1":
        os.environ["HKF_IN_NETNS"] = "1"
        wrapper = os.path.join(e2e.ROOT, "tools", "lcm-netns")
        os.execv(wrapper, [wrapper, sys.executable, os.path.abspath(__file__)] + sys.argv[1:])
    build, out = os.path.abspath(args.build), os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    clips = [clip_points(build, out, name) for name in e2e.REPORT_CLIPS]
    lines = ["# The jitter-error frontier, end to end", "",
             "Made by `dev/eval/e2e_frontier.py`: hkf with the rest measured, and without it its still_wander swept, "
             "through the live chain, the 1 euro "
             "filter's grid on the same raw stream as it arrives, 30 fps, roll.", ""]
    for clip in clips:
        lines += report_lines(*clip)
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out, "frontier.md"), "w") as f:
        f.write(text)
    print(text)
    plot(os.path.join(out, "e2e_frontier.png"), clips)
    e2e.log(f"table in {out}/frontier.md, picture in {out}/e2e_frontier.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
