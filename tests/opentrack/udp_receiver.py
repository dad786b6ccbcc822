#!/usr/bin/env python3
"""A stand-in for opentrack's "UDP over network" input: binds HOST:PORT and writes
every datagram it receives as one line of hex to OUT, until SIGINT/SIGTERM or
--seconds. Writes OUT.ready once bound, so a test knows when to start sending."""
import argparse
import signal
import socket
import sys
import time


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("out")
    parser.add_argument("--host", default="127.0.0.1")
    parser.add_argument("--port", type=int, default=4242)
    parser.add_argument("--seconds", type=float, default=120.0, help="give up after this long")
    args = parser.parse_args()
    stop = []
    signal.signal(signal.SIGTERM, lambda *_: stop.append(1))
    signal.signal(signal.SIGINT, lambda *_: stop.append(1))
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.bind((args.host, args.port))
    sock.settimeout(0.1)
    open(args.out + ".ready", "w").close()
    count = 0
    deadline = time.monotonic() + args.seconds
    with open(args.out, "w") as out:
        while not stop and time.monotonic() < deadline:
            try:
                data = sock.recv(4096)
            except socket.timeout:
                continue
            except InterruptedError:
                continue
            out.write(data.hex() + "\n")
            out.flush()
            count += 1
    print(f"udp_receiver: {count} datagrams on {args.host}:{args.port}", file=sys.stderr)


if __name__ == "__main__":
    main()
