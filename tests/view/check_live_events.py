#!/usr/bin/env python3
"""What the live view's page was sent during view_live_test.sh, checked: events before the commands
(EVENTS1) and after them (EVENTS2), hkf-track's terminal output, the picture fetched.
usage: check_live_events.py EVENTS1.jsonl EVENTS2.jsonl TRACK.txt PICTURE.jpg"""
import json
import re
import statistics
import sys


def load(path):
    with open(path) as f:
        return [json.loads(line) for line in f]


def check(ok, what):
    if not ok:
        sys.exit("check_live_events: " + what)


def main():
    before, after = load(sys.argv[1]), load(sys.argv[2])
    with open(sys.argv[3]) as f:
        terminal = set(line.rstrip("\n") for line in f)
    with open(sys.argv[4], "rb") as f:
        picture = f.read()
    kinds = lambda events, t: [e for e in events if e["event"]["t"] == t]
    raw = [e["event"] for e in kinds(before, "raw")]
    check(any(r["model"] == "mesh_pnp" and r["valid"] for r in raw), "no valid mesh_pnp measurement reached the page")
    poses = [e["event"] for e in kinds(before, "pose")]
    check(any(p["status"] == "TRACKING" for p in poses), "no TRACKING pose reached the page")
    check(kinds(before, "status"), "no rest status reached the page")
    lines = [e["event"]["text"] for e in kinds(before, "line") + kinds(after, "line")]
    check(len(lines) >= 2, f"{len(lines)} status lines")
    shown = [line for line in lines if line in terminal]
    check(len(shown) == len(lines), f"{len(lines) - len(shown)} of the page's lines are not hkf-track's: {lines[:2]}")

    # pictures: the rate, and capture -> page (the picture's capture stamp against the event's arrival)
    # live pictures only: a new stream first replays the feed's last events (an earlier viewer's pictures among
    # them), and the first live one may come before the estimator was asked
    start = before[0]["arrived"]
    pictures = [p for p in kinds(before, "picture") if p["arrived"] > start + 0.5]
    span = pictures[-1]["arrived"] - pictures[0]["arrived"] if len(pictures) > 1 else 0
    rate = (len(pictures) - 1) / span if span > 0 else 0
    delays = [1000 * (p["arrived"] - p["event"]["utime"] / 1e6) for p in pictures]
    print(f"pictures: {len(pictures)} at {rate:.1f} fps; capture -> page ms p50 {statistics.median(delays):.0f} "
          f"max {max(delays):.0f}")
    check(rate >= 10.0, f"pictures at {rate:.1f} fps, not >= 10")
    check(statistics.median(delays) <= 200 and max(delays) <= 400, "pictures later than 200 ms after capture")
    check(picture[:3] == b"\xff\xd8\xff" and len(picture) > 2000, "picture.jpg is no JPEG")

    # the commands: recentre counted and the centre moved; stillness 3 in use; the save done
    first, last = kinds(before, "status")[-1]["event"], kinds(after, "status")[-1]["event"]
    centre_before, centre_after = kinds(before, "pose")[-1]["event"]["center"], kinds(after, "pose")[-1]["event"]["center"]
    print(f"commands {first['commands']} -> {last['commands']}; centre {centre_before} -> {centre_after}; stillness "
          f"{first['stillness']} -> {last['stillness']}, wander {first['wander']} -> {last['wander']} "
          f"(measured {last['wander_measured']}); saved {last['settings_saved']}")
    check(first["commands"] == 0 and last["commands"] == 3, "the node did not count recentre, stillness and save")
    check(centre_before != centre_after, "the recentre did not move the centre")
    check(last["stillness"] == 3 and last["settings_saved"] == 1 and last["settings_unsaved"] == 0,
          "stillness 3 not in use, or not saved")
    check(last["wander_measured"], "no rest was measured on the clip: the stillness's effect cannot be seen")
    measured = min(max(s - n for s, n in zip(last["rest_spread"], last["rest_noise"])), 0.3)  # hkf_rest.h's w
    check(abs(last["wander"] - 3 * measured) < 1e-3, f"the wander in use {last['wander']} is not 3 x {measured:.4f}")
    print("check_live_events: ok")


if __name__ == "__main__":
    main()
