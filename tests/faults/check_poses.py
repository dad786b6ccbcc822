#!/usr/bin/env python3
"""Checks the HEAD_POSE (and HEAD_POSE_RAW) messages of an LCM log for the
fault tests: nothing non-finite, and the expected states around a fault.
usage: check_poses.py --types DIR LOG CHECK [args]
  finite                      every pose and raw pose finite (prints counts)
  lost-after-silence          every silence of the raw stream (>= coast 0.25 s)
                              is followed by a LOST pose stamped 0.25 s after
                              its last measurement, and TRACKING follows when
                              measurements come back
  follows MODEL               every pose answers a raw measurement of MODEL
Exit 0 when the check passes, 1 when not."""
import argparse
import math
import sys

import lcm


def finite(values):
    return all(math.isfinite(v) for v in values)


def pose_values(p):
    return [p.pitch, p.yaw, p.roll, p.pitch_rate, p.yaw_rate, p.roll_rate, *p.variance, *p.r, *p.center]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--types", required=True)
    parser.add_argument("log")
    parser.add_argument("check", choices=["finite", "lost-after-silence", "follows"])
    parser.add_argument("model", nargs="?")
    args = parser.parse_args()
    sys.path.insert(0, args.types)
    from hkf import head_pose_measurement_t, head_pose_t

    raw, poses = [], []
    for e in lcm.EventLog(args.log, "r"):
        if e.channel == "HEAD_POSE_RAW":
            raw.append(head_pose_measurement_t.decode(e.data))
        elif e.channel == "HEAD_POSE":
            poses.append(head_pose_t.decode(e.data))
    bad = [p.seq for p in poses if not finite(pose_values(p))]
    bad_raw = [m.seq for m in raw if m.valid and not finite([m.pitch, m.yaw, m.roll])]
    states = {s: sum(p.status == s for p in poses) for s in (1, 2, 3)}
    print(f"check_poses: {len(raw)} raw, {len(poses)} poses ({states[1]} TRACKING, {states[2]} COASTING, "
          f"{states[3]} LOST); non-finite: {len(bad)} poses, {len(bad_raw)} raw")
    if bad or bad_raw or not poses:
        return 1
    if args.check == "lost-after-silence":
        measured = sorted(m.utime for m in raw if m.valid)
        silences = [(a, b) for a, b in zip(measured, measured[1:]) if b - a >= 250000]
        if not silences:
            print("check_poses: no silence in the raw stream", file=sys.stderr)
            return 1
        for a, b in silences:
            lost = [p for p in poses if p.status == head_pose_t.LOST and a < p.utime < b]
            # the pose that answers the first measurement back (a LOST pose stamped later than that
            # measurement's capture may be published while it is still on its way: a loaded machine)
            after = [p for p in poses if p.measurement_utime == b]
            if not lost or lost[0].utime != a + 250000 or lost[0].measurement_utime != a:
                print(f"check_poses: no LOST pose 0.25 s into the silence after {a}", file=sys.stderr)
                return 1
            if not after or after[0].status != head_pose_t.TRACKING:
                print(f"check_poses: no TRACKING pose when measurements came back at {b}", file=sys.stderr)
                return 1
            print(f"check_poses: silence of {(b - a) / 1e6:.2f} s: LOST at +0.25 s ({len(lost)} LOST poses), "
                  f"TRACKING again at its end")
    if args.check == "follows":
        ours = {m.utime for m in raw if m.model == args.model}
        others = {m.utime for m in raw if m.model != args.model}
        answered = [p for p in poses if not p.extrapolated]
        strays = [p for p in answered if p.utime not in ours]
        print(f"check_poses: {len(answered)} poses answer measurements; {len(ours)} raw from {args.model}, "
              f"{len(others)} from the other publisher; {len(strays)} poses not from {args.model}")
        if strays or not answered or not others:
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
