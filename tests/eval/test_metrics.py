#!/usr/bin/env python3
"""The evaluation's metrics (dev/eval/metrics.py) and peer filters
(dev/eval/peer_filters.py) on signals whose answers are known: a pure delay
gives that lag, white noise of known sigma the expected jitter, a constant
offset at the centre that offset, and each peer filter its defining response.
usage: test_metrics.py (exit 0 when every check holds)"""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "dev", "eval"))
import metrics  # noqa: E402
import peer_filters  # noqa: E402

RATE = 30.0
failures = []


def check(name, value, expected, tol):
    ok = abs(value - expected) <= tol
    print(f"{'OK  ' if ok else 'FAIL'} {name}: {value:.4f} (expected {expected:.4f} +- {tol:g})")
    if not ok:
        failures.append(name)


def head_motion(t):
    """Smooth head motion: a few sines per axis, up to ~60 deg/s, with pauses."""
    gate = 0.5 * (1.0 + np.tanh(3.0 * np.sin(2 * math.pi * 0.15 * t)))  # moves, then holds
    return np.column_stack([8 * np.sin(2 * math.pi * 0.4 * t) * gate,
                            25 * np.sin(2 * math.pi * 0.3 * t + 0.5) * gate,
                            5 * np.sin(2 * math.pi * 0.5 * t + 1.0) * gate])


def main():
    if len(sys.argv) > 1:
        print(__doc__)
        sys.exit(0 if sys.argv[1] in ("-h", "--help") else 2)
    t = np.arange(0, 30, 1 / RATE)
    truth = head_motion(t)

    # a pure delay of 100 ms gives a lag of 100 ms and nothing left after it
    delayed = head_motion(t - 0.100)
    still, moving = metrics.masks(t, truth)
    delay, residual = metrics.lag(t, delayed, truth, moving)
    check("lag of a pure 100 ms delay, ms", 1000 * delay, 100.0, 2.0)
    check("error left after aligning it, deg", residual, 0.0, 0.05)
    delay0, _ = metrics.lag(t, truth, truth, moving)
    check("lag of the reference itself, ms", 1000 * delay0, 0.0, 1.0)

    # white noise of sigma on a still head: frame-to-frame change sqrt(2) sigma
    rng = np.random.default_rng(1)
    sigma = 0.3
    pose = np.array([2.0, -5.0, 1.0])
    noisy = pose + sigma * rng.standard_normal((len(t), 3))
    ref = metrics.reference(t, noisy)
    still, moving = metrics.masks(t, ref)
    check("still frames found on a still head (fraction)", still.mean(), 1.0, 0.02)
    check("moving frames found on a still head (fraction)", moving.mean(), 0.0, 0.0)
    check("jitter of white noise, deg", metrics.still_jitter(noisy, ref, still), math.sqrt(2) * sigma,
          0.05 * math.sqrt(2) * sigma)
    # a perfectly still output scores only the reference's own residual wobble (the metric's floor)
    check("jitter of the still pose itself (the floor), deg",
          metrics.still_jitter(np.tile(pose, (len(t), 1)), ref, still), 0.015, 0.015)

    # centre hold: the head goes 15 deg away and comes back for 2 s, three times
    yaw = np.where((t % 4.0) < 2.0, 0.0, 15.0)
    away = np.column_stack([np.zeros_like(t), metrics.reference(t, np.column_stack([yaw] * 3))[:, 1],
                            np.zeros_like(t)])
    offset_out = away + np.array([0.0, 3.0, 0.0])
    settle, offset, returns = metrics.centre_hold(t, offset_out, away, np.zeros(3))
    check("returns to the centre found", returns, 7, 0)
    check("centre offset of an output 3 deg off, deg", offset, 3.0, 0.05)
    check("it never settles within 2 deg: settle = the whole window, s", settle, metrics.HOLD_WINDOW_S, 1e-9)
    settle, offset, _ = metrics.centre_hold(t, away, away, np.zeros(3))
    check("an output on the reference settles within a frame, s", settle, 0.0, 1.5 / RATE)

    # RMSE on the circle: 359 vs -1 is no error
    check("RMSE across the yaw seam, deg", float(metrics.rmse([[0, 179.5, 0]], [[0, -179.5, 0]])[1]), 1.0, 1e-9)

    # 1 euro with beta 0 is a first-order low-pass: a unit step reaches 1 - 1/e after tau = 1/(2 pi fc)
    f = peer_filters.OneEuro(min_cutoff=1.0, beta=0.0)
    ts = np.arange(0, 2, 1 / 1000.0)
    out = peer_filters.run(f, ts, np.where(ts[:, None] > 0, 1.0, 0.0) * np.ones(3), np.ones(len(ts), bool))
    tau = 1 / (2 * math.pi)
    check("1 euro (beta 0) step at tau", float(np.interp(tau, ts, out[:, 0])), 1 - math.exp(-1), 0.01)

    # Accela: on a still input it stops within the dead zone; a 10 deg step is followed, without overshoot
    a = peer_filters.Accela(smoothing=1.5)
    ts = np.arange(0, 3, 1 / RATE)
    step = np.where(ts[:, None] >= 0.5, [0.0, 10.0, 0.0], [0.0, 0.0, 0.0])
    out = peer_filters.run(a, ts, step, np.ones(len(ts), bool), tick=peer_filters.OPENTRACK_TICK_S)
    check("Accela after a 10 deg yaw step, 2.5 s on", float(out[-1, 1]), 10.0, 1.5)
    check("Accela never overshoots the step (its largest yaw is at most 10)", float(min(out[:, 1].max(), 10.0)),
          float(out[:, 1].max()), 0.0)

    # EWMA: converges to a held input
    e = peer_filters.Ewma()
    out = peer_filters.run(e, ts, step, np.ones(len(ts), bool), tick=peer_filters.OPENTRACK_TICK_S)
    check("EWMA after a 10 deg yaw step, 2.5 s on", float(out[-1, 1]), 10.0, 0.05)

    print(f"{len(failures)} failed" if failures else "all checks hold")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
