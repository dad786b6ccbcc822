"""Metrics against exact truth (truth_eval.py), for one axis (roll) of a filter's
output on a truth clip. Angles in degrees, times in seconds.

  RMSE moving / still   RMS error on frames where the truth moves faster than
                        10 deg/s / has been still for 0.3 s
  still jitter          RMS frame-to-frame change of the output over
                        consecutive still frames (the truth does not change
                        there, so every change is jitter)
  per move (truth_motion.Move), in a window from the move's end to the next
  move's start (at most 2 s):
    overshoot           the furthest the output goes past the target, in the
                        move's direction (deg, 0 if never), and as a share of
                        the move
    onset delay         when the output has covered 10 % of the move, minus
                        when the truth has (s)
    settling time       from the move's end until the output is within
                        SETTLE_BAND of the target for the rest of the window
                        (s; the window's length if it never settles)
"""
import numpy as np

SETTLE_BAND = 0.5  # deg
ONSET_SHARE = 0.10
MAX_WINDOW_S = 2.0


def rmse(output, truth, mask):
    d = (np.asarray(output) - np.asarray(truth))[mask]
    d = d[np.isfinite(d)]
    return float(np.sqrt(np.mean(d ** 2))) if d.size else float("nan")


def still_jitter(output, still):
    steps = np.diff(np.asarray(output, dtype=float))
    pairs = still[1:] & still[:-1] & np.isfinite(steps)
    return float(np.sqrt(np.mean(steps[pairs] ** 2))) if pairs.any() else float("nan")


def _crossing(t, signal, level, start, stop):
    """The first time in [start, stop] at which signal reaches `level` (rising),
    interpolated between frames; NaN if it does not."""
    idx = np.flatnonzero((t >= start - 1e-9) & (t <= stop + 1e-9))
    for k in range(len(idx)):
        i = idx[k]
        if np.isfinite(signal[i]) and signal[i] >= level:
            if k == 0 or not np.isfinite(signal[idx[k - 1]]):
                return float(t[i])
            j = idx[k - 1]
            return float(t[j] + (level - signal[j]) / (signal[i] - signal[j]) * (t[i] - t[j]))
    return float("nan")


def move_metrics(t, output, truth, move, to_truth, window_end):
    """Overshoot (deg, share), onset delay (s) and settling time (s) of one move.
    to_truth: the truth angle for a turn theta (e.g. theta plus the face's own roll)."""
    t = np.asarray(t, dtype=float)
    out = np.asarray(output, dtype=float)
    start, target = float(to_truth(move.start_angle)), float(to_truth(move.end_angle))
    size = abs(target - start)
    direction = np.sign(target - start)
    progress_out = (out - start) * direction
    progress_truth = (np.asarray(truth, dtype=float) - start) * direction
    onset_truth = _crossing(t, progress_truth, ONSET_SHARE * size, move.t0 - 0.5, window_end)
    onset_out = _crossing(t, progress_out, ONSET_SHARE * size, move.t0 - 0.5, window_end)
    after = (t >= move.t1 - 1e-9) & (t <= window_end + 1e-9) & np.isfinite(out)
    if not after.any():
        return {"overshoot": float("nan"), "overshoot_share": float("nan"), "onset_delay": float("nan"),
                "settle": float("nan")}
    beyond = (out[after] - target) * direction
    overshoot = float(max(0.0, beyond.max()))
    times = t[after]
    outside = np.abs(out[after] - target) > SETTLE_BAND
    if not outside.any():
        settle = 0.0
    elif outside[-1]:
        settle = float(window_end - move.t1)  # never settled in the window
    else:
        settle = float(times[np.flatnonzero(outside)[-1] + 1] - move.t1)
    return {"overshoot": overshoot, "overshoot_share": overshoot / size if size > 0 else float("nan"),
            "onset_delay": onset_out - onset_truth, "settle": settle}


def moves_metrics(t, output, truth, moves, to_truth):
    """move_metrics for every move, each in the hold after it: up to where the
    truth moves again (at most MAX_WINDOW_S)."""
    t = np.asarray(t, dtype=float)
    truth = np.asarray(truth, dtype=float)
    rows = []
    for move in moves:
        target = float(to_truth(move.end_angle))
        later = np.flatnonzero((t > move.t1 + 1e-9) & (np.abs(truth - target) > 1e-6))
        end = min(move.t1 + MAX_WINDOW_S, float(t[later[0] - 1]) if later.size else float(t[-1]))
        rows.append(move_metrics(t, output, truth, move, to_truth, end))
    return rows
