#!/usr/bin/env python3
"""Waits until an LCM log that lcm-logger is writing holds what a live test needs next, instead of
sleeping for a time that assumes a speed: at least COUNT messages on CHANNEL (with STATUS, for
HEAD_POSE; stamped after AFTER_US of the logger's clock, if given). Polls every 0.1 s; the log is read
again from its start each time, and a record cut off at its end (not yet flushed) ends the reading.
usage: wait_for_log.py --types DIR LOG --channel CHAN [--status TRACKING|COASTING|LOST] [--count N]
                       [--after-us T] [--timeout S]
Exit 0 once it is there (the time it took is printed), 1 when the deadline passes first."""
import argparse
import sys
import time

import lcm


def count(log, channel, status, after_us, decode):
    n = 0
    try:
        for e in lcm.EventLog(log, "r"):
            if e.channel != channel or e.timestamp <= after_us:
                continue
            if status is not None and decode(e.data).status != status:
                continue
            n += 1
    except (IOError, OSError, ValueError):  # not yet there, or its last record still being written
        pass
    return n


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--types", required=True)
    parser.add_argument("log")
    parser.add_argument("--channel", required=True)
    parser.add_argument("--status", choices=["TRACKING", "COASTING", "LOST"])
    parser.add_argument("--count", type=int, default=1)
    parser.add_argument("--after-us", type=int, default=0)
    parser.add_argument("--timeout", type=float, default=60.0)
    args = parser.parse_args()
    sys.path.insert(0, args.types)
    from hkf import head_pose_t

    status = getattr(head_pose_t, args.status) if args.status else None
    started = time.monotonic()
    while True:
        n = count(args.log, args.channel, status, args.after_us, head_pose_t.decode)
        waited = time.monotonic() - started
        if n >= args.count:
            print(f"wait_for_log: {n} {args.status or ''} {args.channel} after {waited:.1f} s".replace("  ", " "))
            return 0
        if waited > args.timeout:
            print(f"wait_for_log: {args.log} holds {n} of {args.count} {args.status or ''} {args.channel} messages "
                  f"after {args.timeout:.0f} s", file=sys.stderr)
            return 1
        time.sleep(0.1)


if __name__ == "__main__":
    sys.exit(main())
