#!/usr/bin/env python3
"""Draws raw head poses (an LCM log of hkf.head_pose_measurement_t) against
the filtered ones (hkf-filter's CSV): pitch, yaw and roll over time, PNG. Each
estimator model's measurements (the face mesh's, and WHENet's at big turns) have
a colour and a legend entry of their own.
usage: plot_poses.py RAW.lcmlog FILTERED.csv OUT.png --types BUILD/lcmtypes/python"""
import argparse
import csv
import sys

import lcm
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("raw")
    parser.add_argument("filtered")
    parser.add_argument("out")
    parser.add_argument("--types", required=True)
    parser.add_argument("--title", default="head pose: raw estimate and adaptive Kalman filter")
    args = parser.parse_args()
    sys.path.insert(0, args.types)
    from hkf import head_pose_measurement_t

    try:
        raw = [head_pose_measurement_t.decode(e.data) for e in lcm.EventLog(args.raw, "r") if e.channel == "HEAD_POSE_RAW"]
        with open(args.filtered) as f:
            filtered = [r for r in csv.DictReader(f) if r["extrapolated"] == "0"]
    except (OSError, ValueError, KeyError) as e:
        print(f"plot_poses: {e}", file=sys.stderr)
        return 1
    if not raw or not filtered:
        print("plot_poses: nothing to draw", file=sys.stderr)
        return 1
    t0 = raw[0].utime
    models = list(dict.fromkeys(m.model for m in raw))  # in the order they first appear: the first model first
    colours = dict(zip(models, ["tab:gray", "tab:orange", "tab:green", "tab:purple", "tab:brown"] * 4))
    fig, axes = plt.subplots(3, 1, figsize=(11, 7), sharex=True)
    for ax, name in zip(axes, ("pitch", "yaw", "roll")):
        for model in models:
            mine = [m for m in raw if m.valid and m.model == model]
            if mine:
                ax.plot([(m.utime - t0) / 1e6 for m in mine], [getattr(m, name) for m in mine], ".", markersize=3,
                        color=colours[model], label=f"raw: {model} ({len(mine)} frames)")
        ax.plot([(int(r["utime"]) - t0) / 1e6 for r in filtered], [float(r[name]) for r in filtered], "-",
                color="tab:blue", linewidth=1.5, label="filtered")
        lost = [(m.utime - t0) / 1e6 for m in raw if not m.valid]
        if lost:
            ax.plot(lost, [ax.get_ylim()[0]] * len(lost), "|", color="tab:red", label="no face")
        ax.set_ylabel(f"{name}, deg")
        ax.grid(alpha=0.3)
    axes[0].legend(loc="upper right", fontsize=8)
    axes[-1].set_xlabel("time, s")
    fig.suptitle(args.title)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(f"plot_poses: wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
