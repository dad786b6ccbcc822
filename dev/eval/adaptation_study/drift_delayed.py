#!/usr/bin/env python3
"""The drift rate q (drift_rates.py) measured online with a short delay: a rest test that agrees with the
evaluation's still mask, for HOLD's likelihood from a drift tracker (the player's-lag issue); a study, not
shipped.

drift_online.py's causal envelope read a move's first differences as drift. Here each frame c is judged
HALF frames late, from a window centred on it (HALF frames each side): still when the window's least-squares
slope is below metrics.STILL_SPEED (the norm over the axes, as the evaluation's speed) and has been for
metrics.STILL_SETTLE_S, the evaluation's rule with a local line in place of its 2 Hz zero-phase reference.
Frame c's first and second differences join their powers when c and the two frames before it are still;
the powers are running means over the last RATE_TIME seconds of rest (down to the count while fewer), and
q dt = 3 P1 - P2. Printed per clip: q at the clip's end, the median over its second half, and drift_rates.py's
off-line value on the evaluation's still runs.

usage: drift_delayed.py [--build DIR] [--out DIR] [--half FRAMES] [--rate-time S]
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import evaluate  # noqa: E402
import metrics  # noqa: E402
import wander_scales  # noqa: E402


def window_slopes(t, z, half):
    """Per frame, the least-squares slope (deg/s, per axis) of the window of 2 half + 1 frames centred on it
    (nan where the window does not fit)."""
    slopes = np.full_like(z, np.nan)
    for c in range(half, len(z) - half):
        tw, zw = t[c - half:c + half + 1], z[c - half:c + half + 1]
        tc = tw - tw.mean()
        slopes[c] = (tc[:, None] * (zw - zw.mean(axis=0))).sum(axis=0) / (tc ** 2).sum()
    return slopes


def still_delayed(t, z, half):
    """The delayed rest test per frame: slow (window slope below STILL_SPEED) for STILL_SETTLE_S."""
    slow = np.linalg.norm(np.nan_to_num(window_slopes(t, z, half), nan=np.inf), axis=1) < metrics.STILL_SPEED
    still = np.zeros(len(z), dtype=bool)
    since = None
    for c in range(len(z)):
        since = (since if since is not None else t[c]) if slow[c] else None
        still[c] = since is not None and t[c] - since >= metrics.STILL_SETTLE_S
    return still


def drift_rates_online(t, z, still, rate_time):
    """Per frame, q (deg^2/s per axis) from the powers of the still frames' differences so far (nan before any)."""
    q = np.full_like(z, np.nan)
    p1 = p2 = None
    count = 0
    for c in range(2, len(z)):
        if still[c] and still[c - 1] and still[c - 2]:
            d1, d2 = z[c] - z[c - 1], z[c] - 2 * z[c - 1] + z[c - 2]
            dt = t[c] - t[c - 1]
            count = min(count + 1, max(1, int(round(rate_time / dt))))
            p1 = d1 ** 2 if p1 is None else p1 + (d1 ** 2 - p1) / count
            p2 = d2 ** 2 if p2 is None else p2 + (d2 ** 2 - p2) / count
        if p1 is not None:
            q[c] = np.maximum(3 * p1 - p2, 0.0) / (t[c] - t[c - 1])
    return q


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=os.path.join(evaluate.ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(evaluate.ROOT, "out", "eval"))
    parser.add_argument("--half", type=int, default=7)
    parser.add_argument("--rate-time", type=float, default=10.0)
    args = parser.parse_args()
    fmt = lambda v: " / ".join(f"{x:.3f}" for x in v)  # noqa: E731
    print(f"window {2 * args.half + 1} frames (judged {args.half} frames late), powers over {args.rate_time:g} s of rest")
    print("| clip | still frames: delayed test / evaluation's (both) | q at the end | q, median of the second half "
          "| q off line (drift_rates.py) |")
    print("| --- | --- | --- | --- | --- |")
    for name, tv, zv, runs in wander_scales.still_clips(args.build, args.out):
        still = still_delayed(tv, zv, args.half)
        mask = np.zeros(len(zv), dtype=bool)
        for a, b in runs:
            mask[a:b] = True
        q = drift_rates_online(tv, zv, still, args.rate_time)
        _, excess = wander_scales.wander(zv, runs)
        q_offline = np.maximum(6 * excess[1] / np.median(np.diff(tv)), 0)
        print(f"| {name} | {still.sum()} / {mask.sum()} ({(still & mask).sum()}) | {fmt(q[-1])} | "
              f"{fmt(np.nanmedian(q[len(q) // 2:], axis=0))} | {fmt(q_offline)} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
