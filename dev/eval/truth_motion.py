"""Head motion with exact truth (truth_eval.py): the angle a real face frame is
turned through, frame by frame, along trajectories a driver makes.

A trajectory is theta(t) in degrees at the camera's frame rate, plus the list
of its *moves* - the glances and their returns, each from one hold to the next
- on which the step metrics (overshoot, onset, settling) are measured. Moves
follow a minimum-jerk profile (Flash & Hogan 1985), the shape of a quick human
head movement: theta = a + (b - a)(10 s^3 - 15 s^4 + 6 s^5), s = (t - t0) / T,
whose peak speed is 1.875 |b - a| / T.

Segments, in a seeded random order of a fixed set, so every clip has each:
  hold      the head still (0.6-1.2 s)
  glance    out by 10-40 deg at a peak speed of 150-300 deg/s, a hold, and back
  drift     a slow turn of 5-10 deg over 3 s (2-3 deg/s: what a still-head
            filter must follow, not sit on)
  sine      0.5 Hz, 8-12 deg amplitude, 2 periods
  tremor    small fast motion: 0.3 deg of band-limited noise (4-8 Hz) for 2 s
"""
from dataclasses import dataclass, field

import numpy as np

PEAK_SPEED_LIMIT = 300.0  # deg/s: the fastest glance a driver makes, as the trajectories use


@dataclass
class Move:
    """A minimum-jerk move from angle `start_angle` to `end_angle` over [t0, t1] (s)."""
    t0: float
    t1: float
    start_angle: float
    end_angle: float

    @property
    def size(self):
        return self.end_angle - self.start_angle


@dataclass
class Trajectory:
    t: np.ndarray                  # s, frame times from 0
    theta: np.ndarray              # deg, the turn applied at each frame
    moves: list = field(default_factory=list)
    segments: list = field(default_factory=list)  # (name, t0, t1)


START_REST_S = 2.5  # s: the hold a truth clip starts with: the player's start-up rest (hkf-filter's rest_time, 2 s)
#                    and 0.5 s for the camera's first frames (the face search's first estimate may be off by degrees)


def min_jerk(s):
    """The minimum-jerk position profile on s in [0, 1]."""
    s = np.clip(s, 0.0, 1.0)
    return s ** 3 * (10.0 - 15.0 * s + 6.0 * s ** 2)


class _Builder:
    def __init__(self, fps, rng):
        self.fps, self.rng = fps, rng
        self.values = [0.0]  # theta at frame 0
        self.moves, self.segments = [], []

    @property
    def now(self):
        return (len(self.values) - 1) / self.fps

    @property
    def angle(self):
        return self.values[-1]

    def _append(self, values, name):
        t0 = self.now
        self.values.extend(values)
        self.segments.append((name, t0, self.now))

    def hold(self, seconds, name="hold"):
        n = max(1, int(round(seconds * self.fps)))
        self._append([self.angle] * n, name)

    def move(self, target, peak_speed, name):
        size = abs(target - self.angle)
        duration = max(1.875 * size / peak_speed, 2.0 / self.fps)
        n = max(2, int(np.ceil(duration * self.fps)))
        duration = n / self.fps  # whole frames: the move ends on a frame
        t0, start = self.now, self.angle
        s = np.arange(1, n + 1) / n
        self._append(list(start + (target - start) * min_jerk(s)), name)
        self.moves.append(Move(t0, t0 + duration, start, target))

    def drift(self):
        size = self.rng.uniform(5.0, 10.0) * self.rng.choice([-1.0, 1.0])
        n = int(round(3.0 * self.fps))
        start = self.angle
        s = np.arange(1, n + 1) / n
        self._append(list(start + size * s), "drift")

    def sine(self):
        amplitude = self.rng.uniform(8.0, 12.0)
        n = int(round(4.0 * self.fps))
        start = self.angle
        t = np.arange(1, n + 1) / self.fps
        self._append(list(start + amplitude * np.sin(2.0 * np.pi * 0.5 * t)), "sine")

    def tremor(self):
        n = int(round(2.0 * self.fps))
        noise = self.rng.normal(0.0, 1.0, n + 64)
        spectrum = np.fft.rfft(noise)
        freqs = np.fft.rfftfreq(n + 64, 1.0 / self.fps)
        spectrum[(freqs < 4.0) | (freqs > 8.0)] = 0.0
        band = np.fft.irfft(spectrum, n + 64)[32:32 + n]
        band *= 0.3 / max(np.std(band), 1e-9)
        ramp = np.minimum(1.0, np.minimum(np.arange(1, n + 1), np.arange(n, 0, -1)) / (0.2 * self.fps))
        start = self.angle
        self._append(list(start + band * ramp), "tremor")


def driver_trajectory(seed, fps=30.0, glances=4, max_abs=40.0):
    """A trajectory of holds, `glances` glances-and-returns, a drift, a sine and
    a tremor, every angle within +-max_abs deg, after the player's start-up rest
    (START_REST_S). Deterministic for a seed."""
    rng = np.random.default_rng(seed)
    b = _Builder(fps, rng)
    b.hold(START_REST_S)
    parts = ["glance"] * glances + ["drift", "sine", "tremor"]
    rng.shuffle(parts)
    for part in parts:
        if part == "glance":
            size = rng.uniform(10.0, 40.0)
            out = float(np.clip(b.angle + size * rng.choice([-1.0, 1.0]), -max_abs, max_abs))
            if abs(out - b.angle) < 10.0:  # clipped at the edge: glance the other way
                out = float(np.clip(b.angle - size * np.sign(out - b.angle or 1.0), -max_abs, max_abs))
            home = b.angle
            b.move(out, rng.uniform(150.0, PEAK_SPEED_LIMIT), "glance")
            b.hold(rng.uniform(0.6, 1.2))
            b.move(home, rng.uniform(150.0, PEAK_SPEED_LIMIT), "return")
        elif part == "drift":
            b.drift()
        elif part == "sine":
            b.sine()
        else:
            b.tremor()
        b.hold(rng.uniform(0.6, 1.2))
    theta = np.array(b.values)
    return Trajectory(np.arange(len(theta)) / fps, theta, b.moves, b.segments)


def still_mask(trajectory, settle_s=0.3):
    """Frames where the head has been exactly still for at least settle_s."""
    theta, fps = trajectory.theta, 1.0 / np.median(np.diff(trajectory.t))
    still = np.zeros(len(theta), dtype=bool)
    run = 0
    for i in range(len(theta)):
        run = run + 1 if i > 0 and theta[i] == theta[i - 1] else 0
        still[i] = run >= settle_s * fps
    return still


def moving_mask(trajectory, speed=10.0):
    """Frames where the truth moves faster than `speed` deg/s."""
    v = np.abs(np.gradient(trajectory.theta, trajectory.t))
    return v > speed


def lean_trajectory(seed, fps=30.0, moves=6):
    """Position truth (for head position x, y, z): a zoom (the face nearer or
    farther: scale 0.75-1.35, i.e. a lean in or out) and a sideways shift (as
    a fraction of the frame's width, within +-0.12), each changing by
    minimum-jerk moves of 0.3-0.8 s between holds. Returns (t, scale, shift_x)."""
    rng = np.random.default_rng(seed)
    scale, shift = [1.0], [0.0]
    for _ in range(moves):
        hold = int(round(rng.uniform(0.5, 1.0) * fps))
        scale += [scale[-1]] * hold
        shift += [shift[-1]] * hold
        n = int(round(rng.uniform(0.3, 0.8) * fps))
        s = min_jerk(np.arange(1, n + 1) / n)
        to_scale, to_shift = rng.uniform(0.75, 1.35), rng.uniform(-0.12, 0.12)
        scale += list(scale[-1] + (to_scale - scale[-1]) * s)
        shift += list(shift[-1] + (to_shift - shift[-1]) * s)
    scale += [scale[-1]] * int(fps)
    shift += [shift[-1]] * int(fps)
    return np.arange(len(scale)) / fps, np.array(scale), np.array(shift)


def held_turn_trajectory(seed, fps=30.0, max_abs=40.0, step=10.0, hold_s=1.5, peak_speed=120.0):
    """Held turns (turn_truth.py): after the start-up rest, a staircase out to +max_abs in steps of
    `step` deg with a hold of hold_s at each, one move back to 0, the same to -max_abs and back,
    then two glances, a drift and a sine (truth_motion's driver segments) for the moving error.
    Deterministic for a seed."""
    rng = np.random.default_rng(seed)
    b = _Builder(fps, rng)
    b.hold(START_REST_S)
    for sign in (1.0, -1.0):
        for k in range(1, int(round(max_abs / step)) + 1):
            b.move(sign * k * step, peak_speed, "step")
            b.hold(hold_s)
        b.move(0.0, peak_speed, "return")
        b.hold(hold_s)
    for _ in range(2):
        size = rng.uniform(15.0, max_abs) * rng.choice([-1.0, 1.0])
        b.move(size, rng.uniform(150.0, PEAK_SPEED_LIMIT), "glance")
        b.hold(rng.uniform(0.6, 1.2))
        b.move(0.0, rng.uniform(150.0, PEAK_SPEED_LIMIT), "return")
        b.hold(rng.uniform(0.6, 1.2))
    b.drift()
    b.hold(0.6)
    b.sine()
    b.hold(1.0)
    theta = np.array(b.values)
    return Trajectory(np.arange(len(theta)) / fps, theta, b.moves, b.segments)
