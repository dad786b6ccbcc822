"""Truth clips from real faces: a real video frame, or a whole real
clip, moved by a known in-plane transform on every frame, with fresh sensor
noise and JPEG compression each time, written as a folder of images that
`hkf-estimator --source DIR --fps F` reads as a camera would.

An in-plane rotation of the image by theta about the face centre is the head
turned by theta about the line of sight through that centre (the optical
axis for a face in the middle of the image). In hkf's angles (R = Ry(yaw)
Rx(pitch) Rz(roll), estimator/src/models/head_rotation.cpp) that is a roll of
exactly theta for a face in the middle looking into the camera; otherwise the
three angles move together, as truth_angles() computes from the face's own
pose (the estimator's reading of the unturned face: its error enters the
truth's changes only through products of small angles). Scale and shift (zoom
and pan) are the same construction for head position (x, y, z); render()
takes all three.

The sign: hkf's roll is positive with the head tilted to the driver's right
(right ear down). The driver's right ear is on the image's left, so that is
the image turned counter-clockwise as seen - OpenCV's positive angle.

Nothing made here is committed: clips are built under the output folder at
run time from ../shared/data/videos.
"""
import os

import numpy as np

SENSOR_NOISE_DN = 2.0  # per pixel and frame, std in 8-bit counts (a webcam in good light)
JPEG_QUALITY = 90      # each frame compressed afresh


def _rotation(pitch, yaw, roll):
    """hkf's head rotation (head -> camera), as estimator/src/models/head_rotation.cpp."""
    p, y, r = np.radians([pitch, yaw, roll])
    ry = np.array([[np.cos(y), 0, np.sin(y)], [0, 1, 0], [-np.sin(y), 0, np.cos(y)]])
    rx = np.array([[1, 0, 0], [0, np.cos(p), np.sin(p)], [0, -np.sin(p), np.cos(p)]])
    rz = np.array([[np.cos(r), np.sin(r), 0], [-np.sin(r), np.cos(r), 0], [0, 0, 1]])
    return ry @ rx @ rz


def _angles(rotation):
    pitch = np.degrees(np.arcsin(np.clip(rotation[1, 2], -1.0, 1.0)))
    roll = np.degrees(np.arctan2(-rotation[1, 0], rotation[1, 1]))
    yaw = np.degrees(np.arctan2(rotation[0, 2], rotation[2, 2]))
    return pitch, yaw, roll


def _turn(axis, angle):
    """The rotation by angle (deg) about a unit axis, in the sense of hkf's roll
    about the optical axis (a right-ear-down turn of a frontal face)."""
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    a = -np.radians(angle)  # hkf's roll matrix turns about +z by -roll
    return np.eye(3) + np.sin(a) * k + (1.0 - np.cos(a)) * (k @ k)


def line_of_sight(centre, frame_size, focal_scale=1.0):
    """The unit ray from the camera through the image point `centre` (px), in
    the estimator's camera (x right, y down, z forward; focal length
    focal_scale times the long side, principal point in the middle)."""
    width, height = frame_size
    f = focal_scale * max(width, height)
    d = np.array([(centre[0] - width / 2.0) / f, (centre[1] - height / 2.0) / f, 1.0])
    return d / np.linalg.norm(d)


def truth_angles(theta, base_pose, axis=(0.0, 0.0, 1.0)):
    """(pitch, yaw, roll) per frame (n, 3) of a face whose own pose is
    base_pose (pitch, yaw, roll) seen in the image turned by theta (deg) about
    its centre: the head turned about the line of sight through that centre
    (`axis`, line_of_sight(); the optical axis for a face in the middle)."""
    base = _rotation(*base_pose)
    axis = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    return np.array([_angles(_turn(axis, a) @ base) for a in np.atleast_1d(theta)])


def read_frames(video, indices=None):
    """Frames (BGR arrays) of a video: those at `indices`, or all."""
    import cv2
    capture = cv2.VideoCapture(video)
    if not capture.isOpened():
        raise RuntimeError(f"cannot read {video}")
    frames, index = {}, 0
    wanted = None if indices is None else set(indices)
    while True:
        ok, frame = capture.read()
        if not ok:
            break
        if wanted is None or index in wanted:
            frames[index] = frame
        index += 1
    capture.release()
    return [frames[i] for i in (sorted(frames) if indices is None else indices) if i in frames]


def render(frame, centre, theta=0.0, scale=1.0, shift=(0.0, 0.0), rng=None):
    """The frame turned by theta deg (counter-clockwise as seen: roll +theta)
    and scaled about `centre` (px), then shifted by `shift` (px); the border
    filled by reflection, so no black corner draws a false edge. With rng:
    Gaussian sensor noise added (SENSOR_NOISE_DN)."""
    import cv2
    m = cv2.getRotationMatrix2D((float(centre[0]), float(centre[1])), float(theta), float(scale))
    m[0, 2] += shift[0]
    m[1, 2] += shift[1]
    out = cv2.warpAffine(frame, m, (frame.shape[1], frame.shape[0]), flags=cv2.INTER_LINEAR,
                         borderMode=cv2.BORDER_REFLECT_101)
    if rng is not None:
        noisy = out.astype(np.float32) + rng.normal(0.0, SENSOR_NOISE_DN, out.shape).astype(np.float32)
        out = np.clip(np.rint(noisy), 0, 255).astype(np.uint8)
    return out


def write_jpeg(path, image):
    import cv2
    ok, data = cv2.imencode(".jpg", image, [cv2.IMWRITE_JPEG_QUALITY, JPEG_QUALITY])
    if not ok:
        raise RuntimeError(f"cannot encode {path}")
    with open(path, "wb") as f:
        f.write(data.tobytes())


def write_still_clip(folder, frame, centre, theta, seed, scale=None, shift=None):
    """One real frame turned along theta (deg per frame) - and, for position,
    zoomed by scale and moved by shift (px, per frame) - a folder of JPEGs."""
    os.makedirs(folder, exist_ok=True)
    rng = np.random.default_rng(seed)
    for i, angle in enumerate(theta):
        s = 1.0 if scale is None else scale[i]
        d = (0.0, 0.0) if shift is None else shift[i]
        write_jpeg(os.path.join(folder, f"{i:05d}.jpg"), render(frame, centre, angle, s, d, rng=rng))


def write_moving_clip(folder, frames, centres, theta, seed):
    """A whole real clip (its own motion kept), each frame turned by theta
    about that frame's face centre: the real-motion variant."""
    os.makedirs(folder, exist_ok=True)
    rng = np.random.default_rng(seed)
    for i, (frame, centre, angle) in enumerate(zip(frames, centres, theta)):
        write_jpeg(os.path.join(folder, f"{i:05d}.jpg"), render(frame, centre, angle, rng=rng))
