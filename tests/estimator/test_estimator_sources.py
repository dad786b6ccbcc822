#!/usr/bin/env python3
"""hkf-estimator on real videos and images, its output recorded with LCM's
file:// provider and checked message by message:
- a video without a face: every frame published, all valid = false;
- videos where the face leaves and comes back: both states, in the right order;
- a face video: a face in (nearly) every frame, capture times increasing;
- a photo of five people: the estimator locks onto the largest face, does not
  hop to another when it disappears, takes it back when it returns, and only
  after 2 s without it takes another face;
- a folder of images as a source, --max-frames, and bad sources.
usage: test_estimator_sources.py BUILD_DIR SOURCE_DIR MODELS_DIR
"""
import os
import subprocess
import sys
import tempfile

from PIL import Image, ImageDraw

build, source, models = sys.argv[1:4]
sys.path.insert(0, os.path.join(build, "lcmtypes", "python"))
import lcm  # noqa: E402
from hkf import head_pose_measurement_t  # noqa: E402

estimator = os.path.join(build, "estimator", "hkf-estimator")
testdata = os.path.join(models, "testdata")
work = tempfile.mkdtemp()
passed = failed = 0


def check(condition, what):
    global passed, failed
    print(("ok   " if condition else "FAIL ") + what)
    passed, failed = passed + bool(condition), failed + (not condition)


def run(src, *extra):
    """Runs the estimator on src; returns (exit code, output, the first model's measurements:
    one per frame; the second model's, on the same channel, are second_model_test.sh's)."""
    log = os.path.join(work, "out.lcmlog")
    if os.path.exists(log):
        os.unlink(log)
    # the sources are what is tested: no second model (its inference would only cost time)
    p = subprocess.run([estimator, "--source", src, "--second-model", "none", "--lcm-url", f"file://{log}?mode=w", *extra],
                       capture_output=True, text=True, timeout=600)
    messages = []
    if os.path.exists(log):
        first = extra[extra.index("--model") + 1] if "--model" in extra else "mesh_pnp"
        messages = [m for m in (head_pose_measurement_t.decode(e.data) for e in lcm.EventLog(log, "r") if e.channel == "HEAD_POSE_RAW")
                    if m.model == first]
    return p.returncode, p.stdout + p.stderr, messages


def frames_in(output):
    return int(output.split(" frames, ")[0].rsplit(" ", 1)[-1]) if " frames, " in output else -1


# no face at all
code, out, msgs = run(os.path.join(testdata, "no_face.mp4"), "--max-frames", "30")  # each costs a full-frame search
check(code == 0 and len(msgs) == frames_in(out) > 0, f"no_face.mp4: every frame published ({len(msgs)})")
check(msgs and not any(m.valid for m in msgs), "no_face.mp4: all valid = false")

# the face leaves / arrives
for name, first_face in (("face_noface.mov", True), ("noface_face.mov", False)):
    code, out, msgs = run(os.path.join(testdata, name))
    valid = [m.valid for m in msgs]
    check(code == 0 and len(msgs) == frames_in(out) > 0, f"{name}: every frame published ({len(msgs)})")
    check(any(valid) and not all(valid), f"{name}: frames with and without a face ({sum(valid)} of {len(valid)} with)")
    n = len(valid)  # away from the ends (the last frame of noface_face.mov is black)
    head, tail = valid[:int(0.4 * n)], valid[int(0.6 * n):int(0.95 * n)]
    expected = (all(head), not any(tail)) if first_face else (not any(head), all(tail))
    check(expected == (True, True), f"{name}: the face is there {'first' if first_face else 'last'}")
    check(all(m.detection_score == 0 and m.face_box[2] == 0 for m in msgs if not m.valid),
          f"{name}: frames without a face carry no box")

# a face video, with each estimator: valid frames, increasing capture time and seq, the model's id
code, out, msgs = run(os.path.join(testdata, "single_face.mp4"))
check(code == 0 and sum(m.valid for m in msgs) >= 0.95 * len(msgs) > 0 and all(m.model == "mesh_pnp" for m in msgs),
      f"single_face.mp4, default model mesh_pnp: a face in >= 95% of {len(msgs)} frames")
code, out, msgs = run(os.path.join(testdata, "single_face.mp4"), "--model", "whenet")
check(code == 0 and sum(m.valid for m in msgs) >= 0.95 * len(msgs) > 0, f"single_face.mp4: a face in >= 95% of {len(msgs)} frames")
check(all(b.utime > a.utime and b.seq == a.seq + 1 for a, b in zip(msgs, msgs[1:])), "single_face.mp4: utime and seq increase")
check(all(m.model == "whenet" for m in msgs), "single_face.mp4: model id whenet")
check(all(-99 <= m.pitch <= 99 and -180 <= m.yaw <= 180 and -99 <= m.roll <= 99 for m in msgs if m.valid),
      "single_face.mp4: angles in range")

# locking onto one face: a photo of five people (faces at a distance), the
# locked face painted over and back; with the default search (RetinaFace) and
# with BlazeFace full range alone
photo = Image.open(os.path.join(testdata, "multi_face.jpg")).convert("RGB")
single = os.path.join(work, "one")
os.makedirs(single)
photo.save(os.path.join(single, "0000.png"))
for detector in ((), ("--detector", "full")):
    name = "lock" + (" (--detector full)" if detector else " (default)")
    code, out, msgs = run(single, *detector)
    check(code == 0 and len(msgs) == 1 and msgs[0].valid, f"{name}: multi_face.jpg: a face found")
    box = tuple(msgs[0].face_box) if msgs else (0, 0, 1, 1)
    hidden = photo.copy()
    w, h = box[2] - box[0], box[3] - box[1]
    ImageDraw.Draw(hidden).rectangle((box[0] - 0.3 * w, box[1] - 0.3 * h, box[2] + 0.3 * w, box[3] + 0.3 * h), fill=(90, 90, 90))
    sequence = os.path.join(work, "sequence")
    os.makedirs(sequence, exist_ok=True)
    # at 10 fps: 5 frames with it, 10 (1 s) without, 5 with it, then 40 (4 s) without
    plan = [photo] * 5 + [hidden] * 10 + [photo] * 5 + [hidden] * 40
    for i, image in enumerate(plan):
        image.save(os.path.join(sequence, f"{i:04d}.jpg"), quality=95)
    code, out, msgs = run(sequence, "--fps", "10", *detector)
    check(code == 0 and len(msgs) == len(plan), f"{name}: every frame published ({len(msgs)} of {len(plan)})")

    def on_locked_face(m):
        return m.valid and abs(m.face_box[0] - box[0]) < 0.3 * w and abs(m.face_box[1] - box[1]) < 0.3 * h

    if len(msgs) == len(plan):
        check(all(on_locked_face(m) for m in msgs[:5]), f"{name}: the largest face, locked")
        check(not any(m.valid for m in msgs[5:15]), f"{name}: no hop to another face while the locked one is gone (1 s)")
        check(all(on_locked_face(m) for m in msgs[15:20]), f"{name}: the same face taken back")
        check(not any(m.valid for m in msgs[20:39]), f"{name}: still no hop within 2 s")
        later = msgs[41:]
        check(later and all(m.valid and not on_locked_face(m) for m in later),
              f"{name}: after 2 s without it, another face is taken")

# the region option: only faces centred inside it
code, out, msgs = run(single, "--detector", "full", "--region", f"0,0,{photo.width},{int(box[1] - 1)}")
check(code == 0 and len(msgs) == 1 and msgs[0].valid and msgs[0].face_box[3] < box[1] + h,
      "region: a face above the largest one is taken instead")

# --max-frames, bad sources
code, out, msgs = run(os.path.join(testdata, "single_face.mp4"), "--max-frames", "7")
check(code == 0 and len(msgs) == 7, "--max-frames 7: 7 frames")
for bad, why in ((os.path.join(work, "nothing.mp4"), "no such file"), (os.path.join(source, "README.md"), "cannot read video"),
                 (work + "/empty_dir", "no images")):
    os.makedirs(work + "/empty_dir", exist_ok=True)
    code, out, msgs = run(bad)
    check(code != 0 and why in out, f"bad source {os.path.basename(bad)}: '{why}', exit {code}")

print(f"{passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
