#!/usr/bin/env python3
"""hkf-demo on its built-in simulated drive: every filter row is there with
numbers, and the numbers say what the demo is for - each filter is stiller
than the raw measurements (still jitter below 60 % of raw) and closer to the
truth on average over the three axes.
usage: demo_output_test.py HKF_DEMO"""
import re
import subprocess
import sys

ROWS = ["raw measurements", "standard KF (constant R)", "adaptive KF (Eq. 8)", "adaptive KF + loop closure",
        "hkf defaults (calibrated)"]


def main():
    out = subprocess.run([sys.argv[1], "--seconds", "20"], capture_output=True, text=True, check=True).stdout
    rows = {}
    for name in ROWS:
        match = re.search(re.escape(name) + r"\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)\s+([\d.]+) \(\s*([\d.]+)%\)\s+([\d.]+)", out)
        assert match, f"no row for '{name}' in:\n{out}"
        pitch, yaw, roll, jitter, share, moving = (float(v) for v in match.groups())
        rows[name] = ((pitch + yaw + roll) / 3.0, jitter, share)
    raw_rmse, raw_jitter, _ = rows["raw measurements"]
    for name in ROWS[1:]:
        rmse, jitter, share = rows[name]
        print(f"{name}: mean RMSE {rmse:.2f} deg (raw {raw_rmse:.2f}), still jitter {jitter:.3f} ({share:.1f} % of raw)")
        assert rmse < raw_rmse, f"{name} is further from the truth than the raw measurements"
        assert jitter < 0.6 * raw_jitter and abs(share - 100.0 * jitter / raw_jitter) < 0.2, f"{name}: jitter"


if __name__ == "__main__":
    main()
