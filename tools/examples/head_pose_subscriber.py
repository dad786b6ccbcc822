#!/usr/bin/env python3
"""A Python simulator's side of hkf, as small as it gets: subscribe the filtered
head pose (hkf.head_pose_t on HEAD_POSE) and turn it into a camera orientation.

Needs only pip (docs/programs.md "Python"):
    python3 -m venv venv && venv/bin/pip install ./lcmtypes/python
    venv/bin/python tools/examples/head_pose_subscriber.py

Prints one line per pose: seq, status, pitch, yaw, roll (deg, relative to the
centre pose, as hkf-opentrack sends them). Stops after --count poses, or when
no pose has come for --timeout seconds (exit 1), or on Ctrl-C.
"""
import argparse
import sys

import lcm
from hkf import head_pose_t

STATUS = {head_pose_t.TRACKING: "TRACKING", head_pose_t.COASTING: "COASTING", head_pose_t.LOST: "LOST"}


def camera_angles(pose):
    """The head's pitch, yaw, roll relative to the driver's centre pose (deg)."""
    yaw = (pose.yaw - pose.center[1] + 180.0) % 360.0 - 180.0
    return pose.pitch - pose.center[0], yaw, pose.roll - pose.center[2]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--lcm-url", default="udpm://239.255.76.67:7667?ttl=0")
    parser.add_argument("--channel", default="HEAD_POSE")
    parser.add_argument("--count", type=int, default=0, help="stop after this many poses (default: never)")
    parser.add_argument("--timeout", type=float, default=0.0, help="give up after this many s without a pose")
    args = parser.parse_args()

    received = 0

    def on_pose(channel, data):
        nonlocal received
        pose = head_pose_t.decode(data)
        pitch, yaw, roll = camera_angles(pose)
        # a simulator would set its camera here, e.g. camera.set_orientation(pitch, yaw, roll)
        print(f"seq={pose.seq} {STATUS.get(pose.status, '?')} pitch={pitch:.3f} yaw={yaw:.3f} roll={roll:.3f}",
              flush=True)
        received += 1

    lc = lcm.LCM(args.lcm_url)
    lc.subscribe(args.channel, on_pose)
    print(f"head_pose_subscriber: listening on {args.channel} at {args.lcm_url}", file=sys.stderr, flush=True)
    try:
        while args.count <= 0 or received < args.count:
            if lc.handle_timeout(int(args.timeout * 1000) if args.timeout > 0 else 1000) == 0 and args.timeout > 0:
                print(f"head_pose_subscriber: no pose on {args.channel} for {args.timeout:g} s", file=sys.stderr)
                return 1
    except KeyboardInterrupt:
        pass
    print(f"head_pose_subscriber: {received} poses", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
