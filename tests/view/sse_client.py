#!/usr/bin/env python3
"""Reads the live view's event stream for a while, as a page would, and writes each event with the wall time
it arrived: one JSON object a line, {"arrived": s, "event": {...}}. Also fetches /picture.jpg once a picture
event came, and the page itself (for its token). usage: sse_client.py BASE_URL SECONDS OUT.jsonl OUT.jpg"""
import json
import sys
import time
import urllib.request


def main():
    base, seconds, out_path, picture_path = sys.argv[1], float(sys.argv[2]), sys.argv[3], sys.argv[4]
    until = time.time() + seconds
    got_picture = False
    with urllib.request.urlopen(base + "/events", timeout=5) as stream, open(out_path, "w") as out:
        while time.time() < until:
            line = stream.readline()
            if not line:
                break
            if not line.startswith(b"data: "):
                continue
            event = json.loads(line[6:])
            out.write(json.dumps({"arrived": time.time(), "event": event}) + "\n")
            if event["t"] == "picture" and not got_picture:
                with urllib.request.urlopen(base + "/picture.jpg", timeout=5) as picture:
                    with open(picture_path, "wb") as f:
                        f.write(picture.read())
                got_picture = True


if __name__ == "__main__":
    main()
