#!/usr/bin/env python3
"""A few hkf-filter settings on the judged real clips, side by side: still jitter as a share of raw's, lag,
and the lag over the best 1 euro setting's at the same jitter (leave_one_out.py's metrics and clips, without
its choosing). For trying a libhkf variant quickly: build it elsewhere, pass that build.

usage: real_clip_probe.py [--build DIR] [--types DIR] SETTING...
SETTING: hkf-filter --set assignments joined by ';' ("" = the defaults), e.g. "still_wander=0.1;start_rate=0.3".
The prototypes/*.patch variants read their extra knob from the environment (HKF_WALK, HKF_TAU, HKF_RATIO,
HKF_MODE; see each patch); they apply to commit 6f0dd12.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import leave_one_out  # noqa: E402

ROOT = leave_one_out.ROOT


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], epilog=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"), help="whose hkf-filter runs")
    parser.add_argument("--types", default=os.path.join(ROOT, "build", "lcmtypes", "python"),
                        help="the generated Python message types")
    parser.add_argument("--out", default=os.path.join(ROOT, "out", "eval"), help="where the raw logs are cached")
    parser.add_argument("settings", nargs="+")
    args = parser.parse_args()
    grid = [(s or "defaults", [o for o in s.split(";") if o]) for s in args.settings]
    work = os.path.join(args.out, "probe")
    os.makedirs(work, exist_ok=True)
    clips = leave_one_out.measure_all(os.path.abspath(args.build), args.out, args.types, work, grid)
    print("| clip | " + " | ".join(label for label, _ in grid) + " |")
    print("| --- | " + " | ".join("---" for _ in grid) + " |")
    for name, clip in clips.items():
        if not leave_one_out.judged(clip):
            continue
        cells = []
        for m in clip["hkf"]:
            share, ratio, _ = leave_one_out.ratios(clip, m)
            cells.append(f"{100 * share:.1f} %, {m['lag_ms']:.0f} ms, {ratio:.2f}x")
        print(f"| {name} | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
