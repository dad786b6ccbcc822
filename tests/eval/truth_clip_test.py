#!/usr/bin/env python3
"""A truth clip made as dev/eval/truth_eval.py makes them, through the real
estimator: one real frame of ../shared/data/videos/d10.mp4 turned along a
short driver trajectory with fresh noise and JPEG per frame. The construction
holds when the estimator's angles follow the truth computed for the turn
(truth_clips.truth_angles: the turn about the line of sight through the face,
on the face's own pose) on all three axes: roll one for one (slope 1 within
3 %, sign included) within 0.8 deg RMS, pitch and yaw within 1.2 deg (the
estimator's own error as the face turns) and yaw closer than a constant.
usage: truth_clip_test.py BUILD_DIR VIDEOS_DIR"""
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "dev", "eval"))
import truth_clips  # noqa: E402
import truth_eval  # noqa: E402
import truth_motion  # noqa: E402


def check_position(build, frame, centre):
    """The same frame zoomed and shifted along truth_motion.lean_trajectory -
    position truth (head x, y, z): the estimator's face box moves with
    the shift one for one and grows with the zoom (BlazeFace's box is not
    exactly proportional to the face's size: the slope is printed, a fact for
    a position taken from the box)."""
    t, scale, shift = truth_motion.lean_trajectory(seed=9)
    shift_px = np.column_stack([shift * frame.shape[1], np.zeros_like(shift)])
    with tempfile.TemporaryDirectory() as work:
        folder = os.path.join(work, "lean")
        truth_clips.write_still_clip(folder, frame, centre, np.zeros_like(scale), seed=9, scale=scale, shift=shift_px)
        log = os.path.join(work, "lean.lcmlog")
        subprocess.run([os.path.join(build, "estimator", "hkf-estimator"), "--source", folder, "--fps", "30",
                        "--second-model", "none", "--lcm-url", f"file://{log}?mode=w"], check=True, capture_output=True)
        _, valid, _, centres = truth_eval.read_raw_with_boxes(log, os.path.join(build, "lcmtypes", "python"))
        boxes = boxes_of(log, os.path.join(build, "lcmtypes", "python"))
    n = min(len(valid), len(scale))
    valid, scale, shift_px, centres, boxes = valid[:n], scale[:n], shift_px[:n], centres[:n], boxes[:n]
    width = boxes[:, 2] - boxes[:, 0]
    ratio = width[valid] / np.median(width[valid & (scale == 1.0)])
    size_slope = np.polyfit(scale[valid], ratio, 1)[0]
    size_r = np.corrcoef(scale[valid], ratio)[0, 1]
    moved = centres[valid, 0] - centre[0]
    shift_slope = np.polyfit(shift_px[valid, 0], moved, 1)[0]
    print(f"position clip: {n} frames, zoom {scale.min():.2f}..{scale.max():.2f}, shift "
          f"{shift_px[:, 0].min():+.0f}..{shift_px[:, 0].max():+.0f} px; face found in {100 * valid.mean():.0f} %; "
          f"box width / unzoomed = {size_slope:.3f} x zoom (r = {size_r:.3f}); box centre moved {shift_slope:.3f} "
          f"x the shift")
    assert valid.mean() >= 0.98, "the face was lost in the position clip"
    assert size_r >= 0.95 and 0.7 <= size_slope <= 1.1, "the face box does not grow with the zoom"
    assert abs(shift_slope - 1.0) <= 0.08, "the face box does not move with the shift"


def boxes_of(log, types):
    import lcm
    sys.path.insert(0, types)
    from hkf import head_pose_measurement_t
    return np.array([head_pose_measurement_t.decode(e.data).face_box for e in lcm.EventLog(log, "r")
                     if e.channel == "HEAD_POSE_RAW"], float)


def main():
    build, videos = sys.argv[1], sys.argv[2]
    video = os.path.join(videos, "d10.mp4")
    with tempfile.TemporaryDirectory() as work:
        # where the face is: the estimator on the first frames of the clip
        first = os.path.join(work, "first.lcmlog")
        subprocess.run([os.path.join(build, "estimator", "hkf-estimator"), "--source", video, "--max-frames", "5",
                        "--second-model", "none", "--lcm-url", f"file://{first}?mode=w"], check=True, capture_output=True)
        _, valid, _, centres = truth_eval.read_raw_with_boxes(first, os.path.join(build, "lcmtypes", "python"))
        assert valid[4], "no face in frame 4 of d10.mp4"
        frame = truth_clips.read_frames(video, [4])[0]
        trajectory = truth_motion.driver_trajectory(seed=5, fps=30.0, glances=2)
        folder = os.path.join(work, "clip")
        truth_clips.write_still_clip(folder, frame, centres[4], trajectory.theta, seed=5)
        log = os.path.join(work, "clip.lcmlog")
        subprocess.run([os.path.join(build, "estimator", "hkf-estimator"), "--source", folder, "--fps", "30",
                        "--second-model", "none", "--lcm-url", f"file://{log}?mode=w"], check=True, capture_output=True)
        _, valid, z, _ = truth_eval.read_raw_with_boxes(log, os.path.join(build, "lcmtypes", "python"))
    theta = trajectory.theta[:len(z)]
    found = valid.mean()
    base = np.median(z[valid & (theta == 0.0)], axis=0)
    axis = truth_clips.line_of_sight(centres[4], (frame.shape[1], frame.shape[0]))
    truth = truth_clips.truth_angles(theta, base, axis)
    slope, _ = np.polyfit(truth[valid, 2], z[valid, 2], 1)
    residual = np.sqrt(np.mean((z[valid] - truth[valid]) ** 2, axis=0))
    naive = np.sqrt(np.mean((z[valid, :2] - base[:2]) ** 2, axis=0))
    print(f"truth clip: {len(theta)} frames, turned {theta.min():+.0f}..{theta.max():+.0f} deg, the face's own pose "
          f"pitch {base[0]:+.1f} yaw {base[1]:+.1f} roll {base[2]:+.1f}; face found in {100 * found:.0f} %; raw roll "
          f"against truth: slope {slope:.3f}; residual RMS pitch {residual[0]:.2f}, yaw {residual[1]:.2f}, "
          f"roll {residual[2]:.2f} deg (pitch and yaw taken as constant instead: {naive[0]:.2f}, {naive[1]:.2f})")
    assert found >= 0.98, "the face was lost in the truth clip"
    assert abs(slope - 1.0) <= 0.03, f"roll follows the truth with slope {slope:.3f}, not 1"
    assert residual[2] <= 0.8, "roll strays from the computed truth"
    check_position(build, frame, centres[4])
    assert (residual[:2] <= 1.2).all(), "pitch or yaw strays from the computed truth"
    assert residual[1] < naive[1], "the computed truth explains yaw no better than a constant"


if __name__ == "__main__":
    main()
