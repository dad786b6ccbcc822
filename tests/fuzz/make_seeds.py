#!/usr/bin/env python3
"""Seed corpora for the fuzzers from real data: fuzz_node_messages gets runs of
the raw poses (and a RECENTER) of an LCM log, in its input format
[kind][length][arrival step, 4 bytes LE][payload]; fuzz_node_log gets pieces of
the log itself (whole, with a RECENTER, cut off), after its [rate] byte;
fuzz_node_config gets the shipped config file and --set lines naming models;
fuzz_estimator_outputs starts from nothing (its input picks sizes and values).
usage: make_seeds.py RAW.lcmlog CONFIG OUT_DIR"""
import os
import shutil
import struct
import sys

import lcm


def main():
    log, config, out = sys.argv[1:4]
    messages = os.path.join(out, "fuzz_node_messages")
    configs = os.path.join(out, "fuzz_node_config")
    os.makedirs(messages, exist_ok=True)
    os.makedirs(configs, exist_ok=True)
    shutil.copy(config, os.path.join(configs, "hkf-filter.conf"))
    with open(os.path.join(configs, "set_lines"), "w") as f:  # --set lines: model names at the rule's edges
        f.write("model.mine-2_b.noise.yaw = 7 4 0 30\nmodel.a b.r_const = 1 2 3\nlc_xi = 5\nr_min = 200\n"
                "model.Abc_def-0123456789abcdefghijklm.noise.roll = 9 3 0 40\nstart_rate = 1e300\n")
    events = [e for e in lcm.EventLog(log, "r") if e.channel == "HEAD_POSE_RAW" and len(e.data) < 256]
    recenter = struct.pack(">qqb", 0x0D6A1A80B0A5B7E2, 0, 1)  # placeholder hash is fine: fuzzing mutates it
    for start in range(0, min(len(events), 300), 30):
        seed, previous = b"", None
        for e in events[start:start + 30]:
            step = 1000 + (e.timestamp - previous if previous is not None else 33333)
            previous = e.timestamp
            seed += bytes([0, len(e.data)]) + struct.pack("<I", max(0, min(step, 2**32 - 1))) + e.data
        seed += bytes([3, len(recenter)]) + struct.pack("<I", 34333) + recenter
        with open(os.path.join(messages, f"log_{start:04d}"), "wb") as f:
            f.write(seed)
    logs = os.path.join(out, "fuzz_node_log")
    os.makedirs(logs, exist_ok=True)
    for start in range(0, min(len(events), 300), 60):
        piece = [log_event(i, e.timestamp, e.channel, e.data) for i, e in enumerate(events[start:start + 20])]
        piece.insert(10, log_event(10, events[start + 9].timestamp + 1, "HEAD_TRACKER_CMD", recenter))
        whole = b"".join(piece)
        for name, rate, body in (("whole", 0, whole), ("rate", 15, whole), ("cut", 0, whole[:len(whole) - 40])):
            with open(os.path.join(logs, f"{name}_{start:04d}"), "wb") as f:
                f.write(bytes([rate]) + body)
    print(f"make_seeds: {len(os.listdir(messages))} message seeds, {len(os.listdir(logs))} log seeds, "
          f"1 config seed in {out}")


def log_event(number, timestamp, channel, data):
    """One event as an LCM log holds it (big-endian): sync word, number, time, lengths, channel, data."""
    channel = channel.encode()
    return struct.pack(">IqqII", 0xEDA1DA01, number, timestamp, len(channel), len(data)) + channel + data


if __name__ == "__main__":
    main()
