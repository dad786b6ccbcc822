#!/usr/bin/env python3
"""Raw pose published -> opentrack datagram received: the latency hkf adds
between an estimator and opentrack (two LCM hops, the filter, the bridge, one
UDP datagram). Publishes hkf.head_pose_measurement_t at RATE Hz and, for each,
waits for the datagram on the UDP port hkf-opentrack sends to.
Run by opentrack_latency.sh inside a private network namespace."""
import argparse
import math
import socket
import struct
import sys
import time

import lcm


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--types", required=True)
    parser.add_argument("--lcm-url", required=True)
    parser.add_argument("--port", type=int, default=4242)
    parser.add_argument("--rate", type=float, default=60.0)
    parser.add_argument("--seconds", type=float, default=10.0)
    args = parser.parse_args()
    sys.path.insert(0, args.types)
    from hkf import head_pose_measurement_t

    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.bind(("127.0.0.1", args.port))
    sock.settimeout(0.5)
    lc = lcm.LCM(args.lcm_url)
    count = int(args.rate * args.seconds)
    latencies, lost, bad = [], 0, 0
    start = time.monotonic()
    for i in range(count):
        m = head_pose_measurement_t()
        m.utime = int(time.time() * 1e6)
        m.seq = i + 1
        m.model = "mesh_pnp"
        m.valid = True
        m.yaw = 20.0 * math.sin(i / args.rate)  # a slow head turn
        sent = time.perf_counter()
        lc.publish("HEAD_POSE_RAW", m.encode())
        try:
            data = sock.recv(64)
            latencies.append((time.perf_counter() - sent) * 1e6)
            bad += len(data) != 48 or not all(math.isfinite(v) for v in struct.unpack("<6d", data))
        except socket.timeout:
            lost += 1
        next_at = start + (i + 1) / args.rate
        time.sleep(max(0.0, next_at - time.monotonic()))
    latencies.sort()
    pick = lambda q: latencies[min(len(latencies) - 1, int(q * len(latencies)))] if latencies else float("nan")
    print(f"rate {args.rate:g} Hz: {count} raw poses sent, {len(latencies)} datagrams received, {lost} lost, "
          f"{bad} malformed; raw publish -> datagram us: p50 {pick(0.5):.0f}, p99 {pick(0.99):.0f}, "
          f"max {pick(1.0):.0f}")
    return 0 if lost == 0 and bad == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
