"""The filters a head-tracking user would pick instead of hkf, written here from
their published descriptions (not from their code):

- the 1 euro filter (Casiez, Roussel, Vogel, CHI 2012): a first-order low-pass
  whose cutoff rises with the filtered speed, fc = min_cutoff + beta |dx|;
- opentrack's Accela: each frame the output moves towards the input at a speed
  (deg/s) read off a gain curve of the distance between them (the three
  rotation axes' distance, less a dead zone, divided by the "smoothing"
  setting), shared between the axes in proportion to each one's distance;
- opentrack's EWMA: an exponential moving average whose time constant falls from
  max_smoothing (still) to min_smoothing (moving) as the recent frame-to-frame
  change grows against its long-run noise (0 to 3 standard deviations).

Each is a class with filter(t, z) -> output angle (3,). run() drives one over a
clip: the 1 euro filter once per measurement, Accela and EWMA as opentrack
runs them, every 4 ms on the latest measurement held (their gains are per
second, and at camera rate alone Accela overshoots).
"""
import math

import numpy as np

from metrics import wrap180


class OneEuro:
    """1 euro filter per axis (yaw differenced on the circle). Parameters as in
    the paper: min_cutoff (Hz), beta (s/deg here: cutoff gain per deg/s of speed),
    d_cutoff (Hz) for the speed estimate."""

    def __init__(self, min_cutoff=1.0, beta=0.0, d_cutoff=1.0):
        self.min_cutoff, self.beta, self.d_cutoff = min_cutoff, beta, d_cutoff
        self.x = self.dx = self.t = None

    @staticmethod
    def alpha(cutoff, dt):
        tau = 1.0 / (2.0 * math.pi * cutoff)
        return 1.0 / (1.0 + tau / dt)

    def filter(self, t, z):
        z = np.asarray(z, dtype=float)
        if self.x is None:
            self.x, self.dx, self.t = z.copy(), np.zeros(3), t
            return self.x.copy()
        dt = max(t - self.t, 1e-6)
        self.t = t
        step = z - self.x
        step[1] = wrap180(step[1])
        self.dx += self.alpha(self.d_cutoff, dt) * (step / dt - self.dx)
        cutoff = self.min_cutoff + self.beta * np.abs(self.dx)
        a = np.array([self.alpha(c, dt) for c in cutoff])
        self.x = self.x + a * step
        self.x[1] = wrap180(self.x[1])
        return self.x.copy()


class Accela:
    """opentrack's Accela for rotation. smoothing: its "rotation smoothing"
    slider (0.05-2.5, default 1.5); dead_zone in deg (default 0.03)."""

    # the rotation gain curve: normalised distance -> deg/s (piecewise linear from 0)
    CURVE_X = np.array([0.0, 0.5, 1.0, 1.5, 2.5, 5.0, 8.0, 9.0])
    CURVE_Y = np.array([0.0, 0.4, 1.5, 8.0, 35.0, 100.0, 200.0, 300.0])

    def __init__(self, smoothing=1.5, dead_zone=0.03):
        self.smoothing, self.dead_zone = smoothing, dead_zone
        self.out = self.t = None

    def filter(self, t, z):
        z = np.asarray(z, dtype=float)
        if self.out is None:
            self.out, self.t = z.copy(), t
            return self.out.copy()
        dt = t - self.t
        self.t = t
        d = z - self.out
        d[1] = wrap180(d[1])
        d = np.where(np.abs(d) > self.dead_zone, d - np.copysign(self.dead_zone, d), 0.0) / self.smoothing
        dist = float(np.linalg.norm(d))
        speed = float(np.interp(dist, self.CURVE_X, self.CURVE_Y))  # flat beyond the last point
        share = np.abs(d) / np.abs(d).sum() if dist > 1e-6 else np.zeros(3)
        self.out = self.out + np.sign(d) * share * speed * dt
        self.out[1] = wrap180(self.out[1])
        return self.out.copy()


class Ewma:
    """opentrack's EWMA with dynamic smoothing. min/max_smoothing are time
    constants in s (defaults 0.02 and 0.7), curve the exponent (0.8)."""

    DELTA_RC = 1.0 / 60.0   # the frame-to-frame change is averaged over ~16 ms
    NOISE_RC_MAX = 60.0     # and its noise over up to the last minute

    def __init__(self, max_smoothing=0.7, min_smoothing=0.02, curve=0.8):
        self.max_smoothing, self.min_smoothing, self.curve = max(max_smoothing, min_smoothing), min_smoothing, curve
        self.out = self.t = None

    def filter(self, t, z):
        z = np.asarray(z, dtype=float)
        if self.out is None:
            self.out, self.t = z.copy(), t
            self.delta, self.noise, self.noise_rc = np.zeros(3), np.zeros(3), 0.0
            return self.out.copy()
        dt = t - self.t
        self.t = t
        self.noise_rc = min(self.noise_rc + dt, self.NOISE_RC_MAX)
        delta_alpha = dt / (dt + self.DELTA_RC)
        noise_alpha = dt / (dt + self.noise_rc)
        target = z.copy()
        d = target - self.out
        wrap = np.abs(d[1]) > 180.0
        if wrap:
            d[1] -= math.copysign(360.0, d[1])
            target[1] -= math.copysign(360.0, target[1])
        self.delta += delta_alpha * (d - self.delta)
        noise = self.delta ** 2
        self.noise = noise_alpha * noise + (1.0 - noise_alpha) * self.noise
        with np.errstate(divide="ignore", invalid="ignore"):
            norm = np.where(self.noise < 1e-10, 0.0, np.minimum(noise / (9.0 * self.noise), 1.0))
        smoothing = 1.0 - norm ** self.curve
        rc = self.min_smoothing + smoothing * (self.max_smoothing - self.min_smoothing)
        self.out = self.out + dt / (dt + rc) * (target - self.out)
        self.out[1] = wrap180(self.out[1])
        return self.out.copy()


OPENTRACK_TICK_S = 0.004  # opentrack's pipeline runs its filter every 4 ms on the latest pose


def run(filter_obj, t, z, valid, tick=None):
    """The filter over a clip: its output at each frame's time (NaN before the
    first measurement). Without `tick`, the filter sees each measurement once (the
    1 euro filter's use). With `tick` (s), it runs as in opentrack's pipeline:
    every tick on the latest measurement held, a tick at each arrival."""
    out = np.full((len(t), 3), np.nan)
    last = held = None
    next_tick = None
    for i in range(len(t)):
        if tick is not None and held is not None:
            while next_tick < t[i] - 1e-9:
                last = filter_obj.filter(float(next_tick), held)
                next_tick += tick
        if valid[i]:
            held = np.asarray(z[i], dtype=float)
            last = filter_obj.filter(float(t[i]), held)
            next_tick = t[i] + (tick or 0.0)
        if last is not None:
            out[i] = last
    return out
