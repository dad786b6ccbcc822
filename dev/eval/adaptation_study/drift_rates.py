#!/usr/bin/env python3
"""The rate at which a resting head's estimate drifts, per clip and axis, for HOLD's likelihood from a drift
tracker (the player's-lag issue; prototypes/hold_likelihood_from_drift.patch).

Model: at rest the measurement is a slowly drifting rest angle plus white frame noise, z_k = r_k + e_k with
r_k - r_k-1 ~ N(0, q dt) and e_k ~ N(0, n) (a local-level model). Then the first difference has
E[d1^2] = 2 n + q dt and the second (what hkf's calibration reads n from) E[d2^2] = 6 n + 2 q dt, so both
are identified: q dt = 3 E[d1^2] - E[d2^2], n = (E[d2^2] - 2 q dt) / 6. wander_scales.py's Allan excess at
k = 1 frame is E[d1^2] / 2 - E[d2^2] / 6 = q dt / 6, so q = 6 excess_1 / dt. Measured
here on the evaluation's still runs (metrics.masks on the 2 Hz reference), off line; an online form would
take both differences' powers at rest, as the calibration takes the second's.

usage: drift_rates.py [--build DIR] [--out DIR]   (run leave_one_out.py once first for the raw logs)
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import evaluate  # noqa: E402
import wander_scales  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=os.path.join(evaluate.ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(evaluate.ROOT, "out", "eval"))
    args = parser.parse_args()
    print("| clip | still frames (runs) | frame dt | n pitch / yaw / roll, deg^2 | q pitch / yaw / roll, deg^2/s |")
    print("| --- | ---: | ---: | --- | --- |")
    for name, tv, zv, runs in wander_scales.still_clips(args.build, args.out):
        n, excess = wander_scales.wander(zv, runs)
        dt = float(np.median(np.diff(tv)))
        q = np.maximum(6.0 * excess[1] / dt, 0.0)  # excess_1 = E[d1^2] / 2 - E[d2^2] / 6 = q dt / 6
        fmt = lambda v: " / ".join(f"{x:.3f}" for x in v)  # noqa: E731
        print(f"| {name} | {sum(b - a for a, b in runs)} ({len(runs)}) | {dt:.4f} s | {fmt(n)} | {fmt(q)} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
