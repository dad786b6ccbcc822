#!/usr/bin/env python3
"""Reads the live view's event stream as a page does, until what the test waits for has come (or a deadline
passes), and writes each event with the wall time it arrived: one JSON object a line, {"arrived": s, "event":
{...}}. Also fetches /picture.jpg once a picture event came.
usage: sse_client.py BASE_URL DEADLINE_S OUT.jsonl OUT.jpg [--pictures N] [--commands N] [--line] [--measured]
  --pictures N  until N picture events have come after the stream's replay (its first 0.5 s)
  --commands N  until a status says hkf-filter took N commands and saved the settings once
  --line        until a status line has come
  --measured    until a status says a rest was measured (its wander in use)"""
import argparse
import json
import time
import urllib.request


def done(args, events, start):
    live_pictures = sum(1 for arrived, e in events if e["t"] == "picture" and arrived > start + 0.5)
    statuses = [e for _, e in events if e["t"] == "status"]
    return (live_pictures >= args.pictures and (not args.line or any(e["t"] == "line" for _, e in events)) and
            (not args.measured or any(s["wander_measured"] for s in statuses)) and
            (args.commands is None or any(s["commands"] >= args.commands and s["settings_saved"] >= 1
                                          for s in statuses)))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("base")
    parser.add_argument("deadline", type=float)
    parser.add_argument("out")
    parser.add_argument("picture")
    parser.add_argument("--pictures", type=int, default=0)
    parser.add_argument("--commands", type=int)
    parser.add_argument("--line", action="store_true")
    parser.add_argument("--measured", action="store_true")
    args = parser.parse_args()
    start = time.time()
    events, got_picture = [], False
    with urllib.request.urlopen(args.base + "/events", timeout=5) as stream, open(args.out, "w") as out:
        while time.time() < start + args.deadline and not done(args, events, start):
            line = stream.readline()
            if not line:
                break
            if not line.startswith(b"data: "):
                continue
            event = json.loads(line[6:])
            events.append((time.time(), event))
            out.write(json.dumps({"arrived": events[-1][0], "event": event}) + "\n")
            if event["t"] == "picture" and not got_picture:
                with urllib.request.urlopen(args.base + "/picture.jpg", timeout=5) as picture:
                    with open(args.picture, "wb") as f:
                        f.write(picture.read())
                got_picture = True
    if not done(args, events, start):
        raise SystemExit(f"sse_client: what was waited for did not come within {args.deadline:g} s")


if __name__ == "__main__":
    main()
