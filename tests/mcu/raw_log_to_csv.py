#!/usr/bin/env python3
"""An LCM log of raw head poses (HEAD_POSE_RAW) as the CSV make_mcu_sequence
reads: dt_s,valid,pitch,yaw,roll per frame (the first frame's dt is 1/30 s);
with --position, as position_replay reads it: dt_s,valid,x,y,z (valid: a
position measured, z > 0).
usage: raw_log_to_csv.py RAW.lcmlog TYPES_DIR OUT.csv [--position]"""
import sys

import lcm


def main():
    if len(sys.argv) not in (4, 5) or sys.argv[1] in ("-h", "--help") or sys.argv[4:] not in ([], ["--position"]):
        print(__doc__)
        sys.exit(0 if len(sys.argv) == 2 else 2)
    log, types, out = sys.argv[1:4]
    position = sys.argv[4:] == ["--position"]
    sys.path.insert(0, types)
    from hkf import head_pose_measurement_t
    rows, previous = [], None
    for e in lcm.EventLog(log, "r"):
        if e.channel != "HEAD_POSE_RAW":
            continue
        m = head_pose_measurement_t.decode(e.data)
        dt = (m.utime - previous) / 1e6 if previous is not None else 1 / 30
        previous = m.utime
        if position:
            rows.append(f"{dt:.9g},{int(m.valid and m.z > 0)},{m.x:.9g},{m.y:.9g},{m.z:.9g}")
        else:
            rows.append(f"{dt:.9g},{int(m.valid)},{m.pitch:.9g},{m.yaw:.9g},{m.roll:.9g}")
    if not rows:
        sys.exit(f"raw_log_to_csv: no HEAD_POSE_RAW in {log}")
    with open(out, "w") as f:
        f.write("\n".join(rows) + "\n")
    print(f"raw_log_to_csv: {len(rows)} frames -> {out}")


if __name__ == "__main__":
    main()
