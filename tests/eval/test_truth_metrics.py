"""The truth metrics (dev/eval/truth_metrics.py) on filters with a known
response to a step of known size, and the truth trajectories' promises."""
import math
import os
import sys
import unittest

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "dev", "eval"))
import truth_metrics  # noqa: E402
import truth_motion  # noqa: E402

FPS = 1000.0  # fine steps, so the sampled responses are close to the continuous ones


def step_case(size=20.0, t_step=1.0, seconds=3.0):
    t = np.arange(0.0, seconds, 1.0 / FPS)
    truth = np.where(t >= t_step, size, 0.0)
    return t, truth, truth_motion.Move(t_step, t_step, 0.0, size)


def first_order(t, x, tau):
    """y' = (x - y) / tau, exactly discretised."""
    y = np.zeros_like(x)
    a = math.exp(-(t[1] - t[0]) / tau)
    for i in range(1, len(x)):
        y[i] = a * y[i - 1] + (1.0 - a) * x[i]
    return y


def second_order(t, x, omega, zeta):
    """y'' = omega^2 (x - y) - 2 zeta omega y', semi-implicit Euler at 1 kHz."""
    y, v = np.zeros_like(x), 0.0
    dt = t[1] - t[0]
    for i in range(1, len(x)):
        v += dt * (omega ** 2 * (x[i] - y[i - 1]) - 2.0 * zeta * omega * v)
        y[i] = y[i - 1] + dt * v
    return y


class TestStepMetrics(unittest.TestCase):
    def test_first_order_lag(self):
        """A first-order lag of tau on a 20 deg step: no overshoot, 10 % at
        tau ln(1/0.9), within 0.5 deg at tau ln(20/0.5)."""
        tau = 0.1
        t, truth, move = step_case()
        out = first_order(t, truth, tau)
        m = truth_metrics.move_metrics(t, out, truth, move, lambda a: a, t[-1])
        self.assertEqual(m["overshoot"], 0.0)
        self.assertAlmostEqual(m["onset_delay"], tau * math.log(1 / 0.9), delta=0.002)
        self.assertAlmostEqual(m["settle"], tau * math.log(20.0 / 0.5), delta=0.003)

    def test_second_order_overshoot(self):
        """An underdamped second-order system (zeta 0.3) overshoots a step by
        exp(-zeta pi / sqrt(1 - zeta^2)) of its size."""
        zeta = 0.3
        t, truth, move = step_case()
        out = second_order(t, truth, 2.0 * math.pi * 2.0, zeta)
        m = truth_metrics.move_metrics(t, out, truth, move, lambda a: a, t[-1])
        expected = math.exp(-zeta * math.pi / math.sqrt(1.0 - zeta ** 2))
        self.assertAlmostEqual(m["overshoot_share"], expected, delta=0.01)
        self.assertAlmostEqual(m["overshoot"], 20.0 * expected, delta=0.2)

    def test_negative_move_and_offset(self):
        """A move down, with the truth offset by a constant: the same numbers."""
        tau = 0.05
        t, truth, move = step_case(size=-15.0)
        out = first_order(t, truth, tau) + 3.0
        m = truth_metrics.move_metrics(t, out, truth + 3.0, move, lambda a: a + 3.0, t[-1])
        self.assertEqual(m["overshoot"], 0.0)
        self.assertAlmostEqual(m["onset_delay"], tau * math.log(1 / 0.9), delta=0.002)

    def test_the_truth_itself_scores_zero(self):
        traj = truth_motion.driver_trajectory(seed=3)
        rows = truth_metrics.moves_metrics(traj.t, traj.theta, traj.theta, traj.moves, lambda a: a)
        self.assertGreaterEqual(len(rows), 8)
        for r in rows:
            self.assertAlmostEqual(r["overshoot"], 0.0, places=9)
            self.assertAlmostEqual(r["onset_delay"], 0.0, places=9)
            self.assertEqual(r["settle"], 0.0)
        self.assertEqual(truth_metrics.still_jitter(traj.theta, truth_motion.still_mask(traj)), 0.0)

    def test_jitter_and_rmse(self):
        """White noise of sigma on a still truth: jitter sqrt(2) sigma, RMSE sigma."""
        rng = np.random.default_rng(1)
        out = rng.normal(0.0, 0.2, 20000)
        still = np.ones(20000, dtype=bool)
        self.assertAlmostEqual(truth_metrics.still_jitter(out, still), 0.2 * math.sqrt(2.0), delta=0.005)
        self.assertAlmostEqual(truth_metrics.rmse(out, np.zeros(20000), still), 0.2, delta=0.005)


class TestTrajectories(unittest.TestCase):
    def test_driver_trajectory(self):
        """Every segment kind, glances of 10-40 deg at no more than 300 deg/s,
        within +-40 deg, and reproducible from its seed."""
        traj = truth_motion.driver_trajectory(seed=11)
        names = {name for name, _, _ in traj.segments}
        self.assertTrue({"hold", "glance", "return", "drift", "sine", "tremor"} <= names)
        speed = np.abs(np.diff(traj.theta)) * 30.0
        self.assertLessEqual(speed.max(), truth_motion.PEAK_SPEED_LIMIT * 1.05)
        self.assertLessEqual(np.abs(traj.theta).max(), 40.0 + 1e-9)
        glances = [m for m in traj.moves]
        self.assertTrue(all(10.0 - 1e-9 <= abs(m.size) <= 40.0 + 1e-9 for m in glances[::2]))
        again = truth_motion.driver_trajectory(seed=11)
        self.assertTrue(np.array_equal(traj.theta, again.theta))


if __name__ == "__main__":
    unittest.main()
