"""What a head-tracking user feels, measured on a filter's output.

All signals are arrays of shape (frames, 3) in degrees (pitch, yaw, roll), with
the frame times t in seconds. The reference is the raw measurement smoothed
heavily and without phase shift (forward-backward), so it stands in for the
head's motion where no truth exists:

  still jitter  RMS frame-to-frame change of the output, beyond the
                reference's own change, over still frames (where the reference
                moves slower than STILL_SPEED deg/s, and has for STILL_SETTLE_S):
                a slow real drift is not jitter, and a filter that sits still
                through it is off by it
  lag           the delay that best aligns the output with the reference over
                moving frames (faster than MOVING_SPEED deg/s), and the RMS
                error left after that alignment
  centre hold   after the head returns to its centre pose (the reference comes
                back within RETURN_RADIUS of it after being beyond AWAY_RADIUS,
                and stays for HOLD_WINDOW_S): how long until the output is
                within HOLD_RADIUS of the centre, and how far it sits from it
                over the window's last 60 %
  RMSE          against the truth, where a simulation gives one
"""
import numpy as np
from scipy import signal

REFERENCE_CUTOFF_HZ = 2.0  # zero-phase low-pass of the reference
STILL_SPEED = 5.0          # deg/s: below, the head is still
STILL_SETTLE_S = 0.3       # s: a still frame has been still this long (a lagging output may still be catching up before)
MOVING_SPEED = 10.0        # deg/s: above, the head is moving
MAX_LAG_S = 0.5
AWAY_RADIUS = 6.0          # deg from the centre (the shared clips' excursions: 90th percentile 4-24 deg)
HOLD_WINDOW_S = 0.7        # s the head stays at the centre after a return
RETURN_RADIUS = 3.0
HOLD_RADIUS = 2.0


def wrap180(x):
    return (np.asarray(x) + 180.0) % 360.0 - 180.0


def unwrap_yaw(angles):
    """Angles with yaw made continuous (degrees), for differencing and smoothing."""
    a = np.array(angles, dtype=float)
    a[:, 1] = np.degrees(np.unwrap(np.radians(a[:, 1])))
    return a


def reference(t, raw, cutoff_hz=REFERENCE_CUTOFF_HZ):
    """The raw angles low-passed forward and backward (no phase shift): a 2nd-order
    Butterworth at cutoff_hz, at the clip's median frame rate."""
    rate = 1.0 / np.median(np.diff(t))
    b, a = signal.butter(2, cutoff_hz / (rate / 2.0))
    return signal.filtfilt(b, a, unwrap_yaw(raw), axis=0, padlen=min(len(t) - 1, 3 * max(len(a), len(b))))


def speed(t, angles):
    """Angular speed, deg/s (norm over the three axes), per frame."""
    return np.linalg.norm(np.gradient(unwrap_yaw(angles), t, axis=0), axis=1)


def still_jitter(output, ref, still):
    """RMS frame-to-frame change beyond the reference's (deg, per axis) over
    consecutive still frames."""
    steps = np.diff(unwrap_yaw(output), axis=0) - np.diff(unwrap_yaw(ref), axis=0)
    pairs = still[1:] & still[:-1]
    if not pairs.any():
        return float("nan")
    return float(np.sqrt(np.mean(steps[pairs] ** 2)))


def lag(t, output, ref, moving, max_lag=MAX_LAG_S, step=0.001):
    """(delay in s, RMS error in deg after the delay) minimising the RMS of
    output(t) - ref(t - delay) over the moving frames."""
    out = unwrap_yaw(output)
    refu = unwrap_yaw(ref)
    # yaw of both on the same branch
    out[:, 1] += 360.0 * np.round((refu[:, 1] - out[:, 1]).mean() / 360.0)
    frames = np.flatnonzero(moving & (t - t[0] >= max_lag))
    if frames.size == 0:
        return float("nan"), float("nan")
    best = (float("inf"), 0.0)
    for delay in np.arange(-0.05, max_lag + step / 2, step):
        shifted = np.column_stack([np.interp(t[frames] - delay, t, refu[:, a]) for a in range(3)])
        rms = float(np.sqrt(np.mean((out[frames] - shifted) ** 2)))
        if rms < best[0]:
            best = (rms, float(delay))
    return best[1], best[0]


def centre_hold(t, output, ref, centre):
    """(mean seconds to settle, mean offset in deg) over the returns to the centre."""
    dist_ref = np.linalg.norm(wrap180(unwrap_yaw(ref) - centre), axis=1)
    dist_out = np.linalg.norm(wrap180(unwrap_yaw(output) - centre), axis=1)
    settles, offsets = [], []
    away = False
    for i in range(len(t)):
        if dist_ref[i] > AWAY_RADIUS:
            away = True
        elif away and dist_ref[i] < RETURN_RADIUS:
            away = False
            after = np.flatnonzero((t >= t[i]) & (t <= t[i] + HOLD_WINDOW_S))
            if t[after[-1]] - t[i] < 0.9 * HOLD_WINDOW_S or (dist_ref[after] > RETURN_RADIUS).any():
                continue  # the head did not stay at the centre for the window we look at
            inside = np.flatnonzero(dist_out[after] <= HOLD_RADIUS)
            settles.append(t[after[inside[0]]] - t[i] if inside.size else HOLD_WINDOW_S)
            window = after[t[after] >= t[i] + 0.4 * HOLD_WINDOW_S]
            offsets.append(float(np.mean(dist_out[window])))
    if not settles:
        return float("nan"), float("nan"), 0
    return float(np.mean(settles)), float(np.mean(offsets)), len(settles)


def rmse(output, truth):
    """RMS error per axis (deg) against the truth, yaw on the circle."""
    d = wrap180(np.asarray(output) - np.asarray(truth))
    return np.sqrt(np.mean(d ** 2, axis=0))


def masks(t, ref):
    """(still, moving) frame masks from the reference's speed; a still frame ends
    STILL_SETTLE_S of stillness, so what a lagging filter does after a movement
    counts as lag, not jitter."""
    v = speed(t, ref)
    slow = v < STILL_SPEED
    still = np.zeros(len(t), dtype=bool)
    start = None
    for i in range(len(t)):
        if not slow[i]:
            start = None
            continue
        start = t[i] if start is None else start
        still[i] = t[i] - start >= STILL_SETTLE_S
    return still, v > MOVING_SPEED
