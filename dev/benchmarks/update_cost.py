#!/usr/bin/env python3
"""Instructions per filter update, counted by callgrind (repeatable on a noisy machine).

Runs hkf-bench-update under valgrind --tool=callgrind, reads the inclusive
instruction count of each step function, and prints instructions per step side
by side: libhkf (paper settings and constant R), cv::KalmanFilter(6, 3) and an
Eigen fixed-size 6-state filter, all doing the same work on the same input.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

STEPS = [
    ("step_libhkf_paper", "libhkf hkf_update: adaptive R (Eq. 8) + loop closure (Eq. 9)"),
    ("step_libhkf_constant", "libhkf hkf_update: constant R, no loop closure"),
    ("step_libhkf_defaults", "libhkf hkf_update: the defaults (motion adaptation; R at the calibrated noise level)"),
    ("step_libhkf_calibration", "libhkf hkf_calibration_update: the noise calibration beside the defaults"),
    ("step_libhkf_rest", "libhkf hkf_rest_update: the player's rest, while one is measured"),
    ("step_libhkf_pair", "libhkf hkf_update_pair: two estimators' measurements, each with its own Eq. 8 curves"),
    ("step_libhkf_pair_prepared", "libhkf hkf_update_pair_prepared: the same, the second model prepared once"),
    ("step_libhkf_position", "libhkf hkf_position_update: the head's position x, y, z"),
    ("step_libhkf_position_calibration", "libhkf hkf_calibration_update_position: the position's calibration beside it"),
    ("step_eigen", "Eigen fixed-size 6-state filter, same work"),
    ("step_opencv", "cv::KalmanFilter(6, 3) predict + correct, same work"),
]
GOAL = 300


def fail(message):
    print(f"update_cost: {message}", file=sys.stderr)
    sys.exit(1)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("build_dir", help="the CMake build folder (holds dev/benchmarks/hkf-bench-update)")
    parser.add_argument("--steps", type=int, default=20000, help="filter steps per variant (default 20000)")
    args = parser.parse_args()

    bench = os.path.join(args.build_dir, "dev", "benchmarks", "hkf-bench-update")
    if not os.access(bench, os.X_OK):
        fail(f"{bench} is not built (OpenCV and Eigen are needed: scripts/setup.sh)")
    for tool in ("valgrind", "callgrind_annotate"):
        if shutil.which(tool) is None:
            fail(f"{tool} not found (apt-get install valgrind)")

    with tempfile.TemporaryDirectory() as tmp:
        out_file = os.path.join(tmp, "callgrind.out")
        print(f"update_cost: running {args.steps} steps of each filter under callgrind ...", file=sys.stderr)
        run = subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out_file}", bench,
                              str(args.steps)], capture_output=True, text=True)
        if run.returncode != 0:
            fail(f"the benchmark failed:\n{run.stderr[-2000:]}")
        facts = dict(line.split(" ", 1) for line in run.stdout.strip().splitlines())
        annotate = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", out_file],
                                  capture_output=True, text=True, check=True).stdout

    counts = {}
    for name, _ in STEPS:
        match = re.search(r"^\s*([\d,]+)\s+(?:\([^)]*\)\s+)?\S*:" + name + r"\b", annotate, re.MULTILINE)
        if not match:
            fail(f"no count for {name} in the callgrind output")
        counts[name] = int(match.group(1).replace(",", "")) / args.steps

    cpu = "x86-64"
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(l.split(":", 1)[1].strip() for l in f if l.startswith("model name"))
    except (OSError, StopIteration):
        pass
    base = counts["step_libhkf_paper"]
    print(f"Instructions per filter step (callgrind, {args.steps} steps of a simulated drive, {cpu}):\n")
    print("| filter | instructions / step | vs libhkf |")
    print("| --- | ---: | ---: |")
    for name, label in STEPS:
        print(f"| {label} | {counts[name]:,.0f} | {counts[name] / base:.1f}x |")
    print(f"\nlibhkf with the paper's settings: {base:.0f} instructions per update "
          f"(goal <= {GOAL}: {'met' if base <= GOAL else 'NOT met'}).")
    print(f"Same work: loop closure applied on {facts['loop_closures']} of {facts['steps']} steps; largest yaw "
          f"difference from libhkf: OpenCV {float(facts['worst_yaw_difference_opencv']):.1e} deg, "
          f"Eigen {float(facts['worst_yaw_difference_eigen']):.1e} deg.")
    if facts.get("pair_prepared_differences", "0") != "0":
        fail(f"hkf_update_pair_prepared differed from hkf_update_pair on {facts['pair_prepared_differences']} steps")


if __name__ == "__main__":
    main()
