#!/usr/bin/env python3
"""How a resting head's estimate wanders, by time scale, on the real clips (for the player's-lag issue:
measure the wander instead of fixing still_wander).

Per clip (the raw logs leave_one_out.py caches in out/eval/raw/, default model), over the runs of at least
MIN_RUN still frames (metrics.masks on the 2 Hz reference): the frame noise n = E[d^2] / 6 from the second
differences d (what hkf's calibration measures), and, at block lengths k, half the mean squared difference
of consecutive k-frame means (an Allan variance). For white noise that is n / k; what it holds beyond n / k
is wander on that scale, which n does not see.

usage: wander_scales.py [--build DIR] [--out DIR]   (run leave_one_out.py once first for the raw logs)
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import evaluate  # noqa: E402
import metrics  # noqa: E402

MIN_RUN = 12
BLOCKS = (1, 3, 6)


def still_runs(still):
    """(start, end) of each run of at least MIN_RUN still frames."""
    runs, start = [], None
    for i, s in enumerate(list(still) + [False]):
        if s and start is None:
            start = i
        elif not s and start is not None:
            if i - start >= MIN_RUN:
                runs.append((start, i))
            start = None
    return runs


def wander(z, runs):
    """n per axis, and per block length k the Allan variance's excess over n / k (deg^2)."""
    n = np.mean(np.concatenate([np.diff(z[a:b], 2, axis=0) for a, b in runs]) ** 2, axis=0) / 6
    excess = {}
    for k in BLOCKS:
        steps = []
        for a, b in runs:
            blocks = (b - a) // k
            if blocks >= 2:
                steps.append(np.diff(z[a:a + blocks * k].reshape(blocks, k, 3).mean(axis=1), axis=0))
        excess[k] = 0.5 * np.mean(np.concatenate(steps) ** 2, axis=0) - n / k
    return n, excess


def still_clips(build, out):
    """(name, frame times, measurements with yaw unwrapped, still runs) per clip with still runs, from the raw logs
    leave_one_out.py caches in OUT/raw/ (the default model)."""
    types = os.path.join(build, "lcmtypes", "python")
    for path in evaluate.clips():
        name = os.path.splitext(os.path.basename(path))[0]
        raw = os.path.join(out, "raw", f"{name}.mesh_pnp.lcmlog")
        if not os.path.exists(raw):
            continue
        _, t, valid, z = evaluate.read_raw(raw, types)
        tv, zv = t[valid], metrics.unwrap_yaw(z[valid])
        still, _ = metrics.masks(tv, metrics.reference(tv, zv))
        runs = still_runs(still)
        if runs:
            yield name, tv, zv, runs


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--build", default=os.path.join(evaluate.ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(evaluate.ROOT, "out", "eval"))
    args = parser.parse_args()
    print("| clip | still frames (runs) | n pitch / yaw / roll | " +
          " | ".join(f"beyond n/{k}, k = {k}" for k in BLOCKS) + " |")
    print("| --- | ---: | --- |" + " --- |" * len(BLOCKS))
    for name, _, zv, runs in still_clips(args.build, args.out):
        n, excess = wander(zv, runs)
        fmt = lambda v: " / ".join(f"{x:.3f}" for x in v)  # noqa: E731
        print(f"| {name} | {sum(b - a for a, b in runs)} ({len(runs)}) | {fmt(n)} | " +
              " | ".join(fmt(excess[k]) for k in BLOCKS) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
