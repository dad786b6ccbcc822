#!/usr/bin/env python3
"""Compares the hkf.head_pose_t messages of two LCM logs.

Used by the replay test: the HEAD_POSE stream lcm-logger recorded from the
live hkf-filter must have the same count and values as hkf-filter --offline.
Fields that depend on wall-clock time (latency_us) are not compared.
Exit 0 when they match, 1 when not, 2 on bad input.
"""
import argparse
import math
import sys

import lcm

COMPARED = ["utime", "measurement_utime", "seq", "status", "pitch", "yaw", "roll", "pitch_rate", "yaw_rate",
            "roll_rate", "variance", "r", "center", "loop_closure_active", "extrapolated"]


def poses(path, channel, head_pose_t):
    return [head_pose_t.decode(e.data) for e in lcm.EventLog(path, "r") if e.channel == channel]


def differ(a, b, tolerance):
    if isinstance(a, (list, tuple)):
        return any(differ(x, y, tolerance) for x, y in zip(a, b))
    if isinstance(a, float):
        return not (math.isfinite(a) and math.isfinite(b) and abs(a - b) <= tolerance * max(1.0, abs(b)))
    return a != b


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("expected", help="LCM log, e.g. from hkf-filter --offline")
    parser.add_argument("actual", help="LCM log, e.g. recorded by lcm-logger")
    parser.add_argument("--types", required=True, help="folder holding the generated Python package hkf")
    parser.add_argument("--channel", default="HEAD_POSE")
    parser.add_argument("--tolerance", type=float, default=1e-5, help="relative tolerance of float fields")
    args = parser.parse_args()
    sys.path.insert(0, args.types)
    from hkf import head_pose_t

    try:
        expected = poses(args.expected, args.channel, head_pose_t)
        actual = poses(args.actual, args.channel, head_pose_t)
    except (OSError, ValueError) as e:
        print(f"compare_pose_logs: {e}", file=sys.stderr)
        return 2
    print(f"compare_pose_logs: {len(expected)} expected, {len(actual)} recorded {args.channel} messages")
    if len(expected) != len(actual):
        print("compare_pose_logs: the counts differ", file=sys.stderr)
        return 1
    if not expected:
        print("compare_pose_logs: no messages to compare", file=sys.stderr)
        return 1
    for i, (e, a) in enumerate(zip(expected, actual)):
        for field in COMPARED:
            if differ(getattr(e, field), getattr(a, field), args.tolerance):
                print(f"compare_pose_logs: message {i}: {field} {getattr(a, field)} != {getattr(e, field)}",
                      file=sys.stderr)
                return 1
    print("compare_pose_logs: identical within tolerance")
    return 0


if __name__ == "__main__":
    sys.exit(main())
