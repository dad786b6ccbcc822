"""The end-to-end frontier's choices (dev/eval/e2e_frontier.py): the least error within a jitter share, and
the 1 euro grid's edges, on points with known answers."""
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "dev", "eval"))
import e2e_frontier  # noqa: E402


def point(name, jitter, error):
    return name, {"jitter": jitter, "at_arrival": error}


POINTS = [point("stiff", 0.02, 1.5), point("middle", 0.09, 0.8), point("quick", 0.25, 0.5),
          point("broken", 0.01, float("nan"))]


class BestWithin(unittest.TestCase):
    def test_least_error_within_the_share(self):
        best = e2e_frontier.best_within(POINTS, 1.0, 0.10)
        self.assertEqual(best[1], "middle")
        self.assertAlmostEqual(best[0], 0.8)
        self.assertAlmostEqual(best[2], 0.09)
        self.assertEqual(e2e_frontier.best_within(POINTS, 1.0, 0.30)[1], "quick")

    def test_shares_are_of_raws_jitter(self):
        self.assertEqual(e2e_frontier.best_within(POINTS, 0.5, 0.10)[1], "stiff")  # 0.09 is 18 % of 0.5

    def test_none_within_and_no_error_skipped(self):
        self.assertIsNone(e2e_frontier.best_within(POINTS, 1.0, 0.015))  # only the point without an error


class GridEdges(unittest.TestCase):
    def test_edges_named(self):
        low = min(e2e_frontier.ONE_EURO_MIN_CUTOFF)
        high = max(e2e_frontier.ONE_EURO_D_CUTOFF)
        self.assertEqual(e2e_frontier.at_edges(f"min_cutoff {low:g}, beta 0.2, d_cutoff {high:g}"),
                         ["min_cutoff", "d_cutoff"])
        self.assertEqual(e2e_frontier.at_edges("min_cutoff 0.5, beta 1, d_cutoff 2"), [])
        self.assertEqual(e2e_frontier.at_edges("min_cutoff 0.5, beta 0, d_cutoff 2"), ["beta"])


if __name__ == "__main__":
    unittest.main()
