#!/usr/bin/env bash
# The position filter in every numeric type on a shared clip (the libhkf issue's goal: Q16.16 within
# 0.05 cm of the double build): hkf-estimator's positions of d10.mp4 -> position_replay built for float,
# double and Q16.16 (defaults, the noise calibration beside) -> the largest difference from double per type.
# Exit 77 (skipped) without the clip.
# usage: position_types_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd)
clip=$source/../shared/data/videos/d10.mp4
[ -s "$clip" ] || { echo "SKIP: no $clip"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$build/estimator/hkf-estimator" --source "$clip" --lcm-url "file://$work/raw.lcmlog?mode=w" >/dev/null 2>&1 \
  || { echo "FAIL: hkf-estimator on $clip" >&2; exit 1; }
"$source/.venv/bin/python" "$source/tests/mcu/raw_log_to_csv.py" "$work/raw.lcmlog" "$build/lcmtypes/python" \
  "$work/positions.csv" --position
for real in double float fixed; do
  "$build/tests/position_replay_$real" "$work/positions.csv" "$work/$real.txt"
done
"$source/.venv/bin/python" - "$work" <<'PY'
import sys
import numpy as np
work = sys.argv[1]
double = np.loadtxt(f"{work}/double.txt", ndmin=2)
failed = False
if len(double) < 300:
    sys.exit(f"FAIL: only {len(double)} positions of d10 (expected most of its 448 frames)")
for real, bound in (("float", 0.05), ("fixed", 0.05)):
    other = np.loadtxt(f"{work}/{real}.txt", ndmin=2)
    if other.shape != double.shape:
        sys.exit(f"FAIL: {real} gave {len(other)} positions, double {len(double)}")
    worst = np.abs(other - double).max(axis=0)
    ok = worst.max() <= bound
    failed |= not ok
    print(f"{'ok  ' if ok else 'FAIL'} {real}: {len(double)} positions of d10, largest difference from double "
          f"x {worst[0]:.4f}, y {worst[1]:.4f}, z {worst[2]:.4f} cm (<= {bound})")
sys.exit(1 if failed else 0)
PY
