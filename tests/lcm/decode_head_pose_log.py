"""The Python twin of DecodeHeadPoseLog.java: count, first yaw, yaw sum."""
import sys

sys.path.insert(0, sys.argv[2])  # tools/logs
sys.path.insert(0, sys.argv[3])  # generated Python types
import lcmlog  # noqa: E402
from hkf import head_pose_t  # noqa: E402

yaws = [head_pose_t.decode(e.data).yaw for e in lcmlog.read_events(sys.argv[1]) if e.channel == "HEAD_POSE"]
total = 0.0
for y in yaws:
    total += y
print("%d %.6f %.4f" % (len(yaws), yaws[0] if yaws else 0.0, total))
