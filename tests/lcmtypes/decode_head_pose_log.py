"""The Python twin of DecodeHeadPoseLog.java: count, first yaw, yaw sum."""
import sys

import lcm

sys.path.insert(0, sys.argv[2])  # generated Python types
from hkf import head_pose_t  # noqa: E402

yaws = [head_pose_t.decode(e.data).yaw for e in lcm.EventLog(sys.argv[1], "r") if e.channel == "HEAD_POSE"]
total = 0.0
for y in yaws:
    total += y
print("%d %.6f %.4f" % (len(yaws), yaws[0] if yaws else 0.0, total))
