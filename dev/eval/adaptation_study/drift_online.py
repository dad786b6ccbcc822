#!/usr/bin/env python3
"""The drift rate q (drift_rates.py) measured online, causally, as hkf's calibration measures n: per axis the
powers of the first and second differences, each low-passed (time constant TIME) and followed by its lower
envelope (down at once, up by at most the factor 1 + RISE dt a step, so that a move does not pass for noise),
then q dt = 3 P1 - P2 (a local-level model: E[d1^2] = 2 n + q dt, E[d2^2] = 6 n + 2 q dt). Printed per clip:
the median of q over the clip's second half, beside drift_rates.py's off-line value on the still runs; a study
for the player's-lag issue, not shipped.

usage: drift_online.py [--build DIR] [--out DIR] [--time S] [--rise PER_S]
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import evaluate  # noqa: E402
import wander_scales  # noqa: E402


def envelope_powers(z, t, time, rise):
    """Per frame and axis, the lower envelopes of the low-passed d1^2 and d2^2 (nan before the history)."""
    p1 = np.full_like(z, np.nan)
    p2 = np.full_like(z, np.nan)
    power1 = power2 = env1 = env2 = None
    for k in range(2, len(z)):
        dt = t[k] - t[k - 1]
        d1 = z[k] - z[k - 1]
        d2 = z[k] - 2 * z[k - 1] + z[k - 2]
        beta = dt / (dt + time)
        if power1 is None:
            power1, power2 = d1 ** 2, d2 ** 2
            env1, env2 = power1.copy(), power2.copy()
        power1 = power1 + beta * (d1 ** 2 - power1)
        power2 = power2 + beta * (d2 ** 2 - power2)
        env1 = np.where(power1 < env1, power1, np.minimum(env1 * (1 + rise * dt), power1))
        env2 = np.where(power2 < env2, power2, np.minimum(env2 * (1 + rise * dt), power2))
        p1[k], p2[k] = env1, env2
    return p1, p2


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=os.path.join(evaluate.ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(evaluate.ROOT, "out", "eval"))
    parser.add_argument("--time", type=float, default=0.3)
    parser.add_argument("--rise", type=float, default=0.2)
    args = parser.parse_args()
    print(f"low-pass {args.time:g} s, envelope rise {args.rise:g} per s")
    print("| clip | q online, median of the second half (pitch / yaw / roll, deg^2/s) | q off line, still runs |")
    print("| --- | --- | --- |")
    for name, tv, zv, runs in wander_scales.still_clips(args.build, args.out):
        p1, p2 = envelope_powers(zv, tv, args.time, args.rise)
        dt = np.median(np.diff(tv))
        q_online = np.maximum(3 * p1 - p2, 0) / dt
        half = q_online[len(q_online) // 2:]
        _, excess = wander_scales.wander(zv, runs)
        q_offline = np.maximum(6 * excess[1] / dt, 0)
        fmt = lambda v: " / ".join(f"{x:.3f}" for x in v)  # noqa: E731
        print(f"| {name} | {fmt(np.nanmedian(half, axis=0))} | {fmt(q_offline)} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
