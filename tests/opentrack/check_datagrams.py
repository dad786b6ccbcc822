#!/usr/bin/env python3
"""Checks what an opentrack receiver got against the HEAD_POSE messages that
lcm-logger recorded: message for message, the exact 48 bytes opentrack expects
(six little-endian doubles x, y, z, yaw, pitch, roll), computed here on their
own from the poses with hkf-opentrack's options. With --flightgear EYE, the
line FlightGear's generic protocol hkf expects instead (the view's heading,
pitch, roll in deg, then the eye's x, y, z in m: FlightGear's conventions,
packaging/flightgear/Protocol/hkf.xml). Exit 0 when equal, 1 when not."""
import argparse
import math
import struct
import sys

import lcm


def opentrack_packet(values):
    return struct.pack("<6d", *values)


def flightgear_line(eye):
    """The line for opentrack's six values: FlightGear looks left for a positive heading, up for a positive pitch,
    rolls the right ear down for a positive roll; x, y, z are the eye's place in the aircraft (x right, y up,
    z aft, m): the aircraft's eye point, the head's x (the image's right: the player's left) taken away."""
    def encode(values):
        x, y, z, yaw, pitch, roll = values
        view = (-yaw, pitch, -roll, eye[0] - 0.01 * x, eye[1] + 0.01 * y, eye[2] + 0.01 * z)
        return ("%.4f,%.4f,%.4f,%.5f,%.5f,%.5f\n" % view).encode()
    return encode


def expected_packets(poses, lost, absolute, invert, scale, encode=opentrack_packet):
    """The datagrams hkf-opentrack must send for these poses, one per pose."""
    packets, last = [], None
    for p in poses:
        if p.status == 3 and lost == "hold":  # LOST: the last datagram again
            if last is not None:
                packets.append(last)
            continue
        if p.status == 3 and lost == "center":
            values = [0.0] * 6
        else:
            pitch, yaw, roll = p.pitch, p.yaw, p.roll
            if not absolute:
                pitch -= p.center[0]
                yaw = math.fmod(yaw - p.center[1] + 180.0, 360.0)
                yaw = (yaw + 360.0 if yaw < 0.0 else yaw) - 180.0
                roll -= p.center[2]
            # opentrack's convention: yaw and pitch as ours, roll negated
            angles = {"yaw": yaw, "pitch": pitch, "roll": -roll}
            # the position: hkf's camera frame is opentrack's x, y, z
            place = {a: getattr(p, a) - (0.0 if absolute else p.position_center[i]) for i, a in enumerate("xyz")}
            values = ([(-place[a] if a in invert else place[a]) * scale.get(a, 1.0) for a in "xyz"] +
                      [(-angles[a] if a in invert else angles[a]) * scale.get(a, 1.0) for a in ("yaw", "pitch", "roll")])
            if not all(math.isfinite(v) for v in values):
                continue  # never sent
        last = encode(values)
        packets.append(last)
    return packets


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("poses", help="LCM log with the HEAD_POSE messages")
    parser.add_argument("datagrams", help="udp_receiver.py's output")
    parser.add_argument("--types", required=True, help="folder holding the generated Python package hkf")
    parser.add_argument("--channel", default="HEAD_POSE")
    parser.add_argument("--lost", default="hold", choices=["hold", "center", "send"])
    parser.add_argument("--absolute", action="store_true")
    parser.add_argument("--invert", default="", help="comma list of axes")
    parser.add_argument("--scale", action="append", default=[], help="AXIS=K")
    parser.add_argument("--flightgear", metavar="X,Y,Z", help="FlightGear's lines, the aircraft's eye point (m)")
    parser.add_argument("--rate", action="store_true", help="fixed-rate sending: every datagram must be one "
                        "of the expected packets, in order, repeats allowed")
    args = parser.parse_args()
    sys.path.insert(0, args.types)
    from hkf import head_pose_t

    poses = [head_pose_t.decode(e.data) for e in lcm.EventLog(args.poses, "r") if e.channel == args.channel]
    scale = {a: float(k) for a, k in (s.split("=") for s in args.scale)}
    encode = flightgear_line([float(v) for v in args.flightgear.split(",")]) if args.flightgear else opentrack_packet
    expected = expected_packets(poses, args.lost, args.absolute, set(filter(None, args.invert.split(","))), scale,
                                encode)
    with open(args.datagrams) as f:
        received = [bytes.fromhex(line.strip()) for line in f if line.strip()]
    print(f"check_datagrams: {len(poses)} poses recorded, {len(expected)} datagrams expected, "
          f"{len(received)} received")
    if not args.flightgear:  # FlightGear's lines are text: compared as bytes below
        if any(len(d) != 48 for d in received):
            print("check_datagrams: a datagram is not 48 bytes", file=sys.stderr)
            return 1
        if any(not all(math.isfinite(v) for v in struct.unpack("<6d", d)) for d in received):
            print("check_datagrams: a non-finite value reached the wire", file=sys.stderr)
            return 1
    if args.rate:
        i = 0
        for n, d in enumerate(received):
            while i < len(expected) and expected[i] != d:
                i += 1
            if i == len(expected):
                print(f"check_datagrams: datagram {n} is not a pose that was due, in order", file=sys.stderr)
                return 1
        return 0 if received else 1
    if not expected or received != expected:
        first = next((i for i, (a, b) in enumerate(zip(received, expected)) if a != b), min(len(received), len(expected)))
        print(f"check_datagrams: differ at datagram {first}", file=sys.stderr)
        return 1
    print("check_datagrams: byte for byte identical")
    return 0


if __name__ == "__main__":
    sys.exit(main())
