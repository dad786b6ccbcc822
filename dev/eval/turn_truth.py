#!/usr/bin/env python3
"""Yaw and pitch truth: real frames made into textured 3D heads (head_render.py)
and turned along known trajectories (truth_motion.held_turn_trajectory: a
staircase of holds out to +-40 deg in yaw, +-30 in pitch, glances, a drift and
a sine), with fresh sensor noise and JPEG on every frame, run through the
default chain: hkf-estimator with both models (the face mesh, WHENet where the
mesh's |yaw| >= 10 deg or it finds no face), then hkf-filter --offline.

The head is one frame per clip, the most frontal face the estimator found in
it. Its rendered turn is R(b + d) R(b)^T, b the mesh's reading of that frame and
d the trajectory's (pitch, yaw) change, so the head's pose is b + d in hkf's
angles; the truth is taken against the mesh's median reading of the rendered
frames where d is 0 (the filter's frame is the first model's).

What the game gets is every pose hkf-filter publishes, in the order published
(the CSV's rows), two for one frame where a second model's measurement is
fused and published at once. Per clip and axis:
- the estimator's reading per model against the turn (slope, residual);
- per hold: the still jitter of the published stream (RMS of its steps) and
  of raw (per frame: the mesh where it measures, else WHENet), their ratio;
- moving error: RMSE where the truth moves faster than 10 deg/s, the filter's
  newest pose per frame against raw's, and the ratio; the same filter's on the
  mesh's measurements alone (its lag without the second model); the excess
  over raw's squared error, and the share of it its largest five frames carry;
- reversals: within each move of the staircase (the truth moving one way), the
  largest step of the published stream against the move;
- hand-over: where WHENet starts or stops measuring, the largest difference
  between the published pose's step from frame to frame and the same filter's
  on the mesh's measurements alone (which has the same lag).
Orders, each as a live camera at 30 fps delivers the frames (the estimator read
the folder faster than that): each mesh measurement 8 ms after its frame's
capture, and each WHENet measurement as late behind it as in the log (this
machine: a frame or more) or 12 ms (a fast CPU).

Tuned on the heads from evaluate.TUNING_CLIPS; the others are held out.

usage: turn_truth.py [--build DIR] [--out DIR] [--heads d14,d3,d10,s20] [--filter PATH]...
writes OUT/turn/{turn.md,turn_rows.csv,turn_contact.png,turn_hold.png} and the clips under OUT/turn/clips.
"""
import argparse
import csv
import os
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import evaluate  # noqa: E402
import head_render  # noqa: E402
import truth_clips  # noqa: E402
import truth_motion  # noqa: E402

FPS = 30.0
HEADS = ["d14", "d3", "d10", "s20"]       # d14 and d3 are tuning clips, d10 and s20 held out
AXES = {"yaw": (1, 40.0), "pitch": (0, 30.0)}  # axis index in (pitch, yaw, roll), the staircase's reach
FIRST, SECOND = "mesh_pnp", "whenet"
FAST_LATE_US = 12000                      # a fast CPU: WHENet's measurement 12 ms after the mesh's
MESH_LATENCY_US = 8000                    # the mesh's measurement after its frame's capture (this machine)
ORDERS = {"this machine": None, "fast CPU": FAST_LATE_US}  # WHENet's lag behind the mesh: as logged, 12 ms
GOALS = {"hold_jitter_share": 0.10, "moving_ratio": 1.0, "reversal_deg": 0.3, "handover_deg": 1.0}


def log(message):
    print(f"turn_truth: {message}", flush=True)


def read_measurements(path, types_dir):
    """Per model: {seq: (utime, valid, (pitch, yaw, roll))}, and the log's events in order."""
    import lcm
    sys.path.insert(0, types_dir)
    from hkf import head_pose_measurement_t
    per_model, events = {}, []
    for event in lcm.EventLog(path, "r"):
        if event.channel != "HEAD_POSE_RAW":
            continue
        m = head_pose_measurement_t.decode(event.data)
        per_model.setdefault(m.model, {})[m.seq] = (m.utime, bool(m.valid), (m.pitch, m.yaw, m.roll), m.face_box)
        events.append((event.timestamp, m.model, m.seq, event.data))
    return per_model, events


def frontal_frame(build, out, clip):
    """The clip's most frontal face: (frame index, mesh pose, face box)."""
    raw = evaluate.raw_log(build, out, clip, FIRST)
    per_model, _ = read_measurements(raw, os.path.join(build, "lcmtypes", "python"))
    frames = per_model[FIRST]
    first_seq = min(frames)
    seq = min((s for s in frames if frames[s][1]), key=lambda s: abs(frames[s][2][0]) + abs(frames[s][2][1]))
    return seq - first_seq, np.array(frames[seq][2], float), frames[seq][3]


def turns(base, axis, theta):
    """The rendered turn per frame: R(base + d) R(base)^T, d = theta on `axis` (deg)."""
    r0 = truth_clips._rotation(*base)
    out = []
    for a in theta:
        d = np.array(base, float)
        d[axis] += a
        out.append(truth_clips._rotation(*d) @ r0.T)
    return out


def write_clip(folder, head, rotations, seed):
    """The head turned frame by frame, noise and JPEG afresh each time."""
    os.makedirs(folder + ".part", exist_ok=True)
    rng = np.random.default_rng(seed)
    for i, turn in enumerate(rotations):
        image = head.render(turn).astype(np.float32)
        image += rng.normal(0.0, truth_clips.SENSOR_NOISE_DN, image.shape).astype(np.float32)
        truth_clips.write_jpeg(os.path.join(folder + ".part", f"{i:05d}.jpg"),
                               np.clip(np.rint(image), 0, 255).astype(np.uint8))
    os.replace(folder + ".part", folder)


def estimate(build, folder, log_path):
    """The default chain's estimator on the folder (both models); the raw log, made once."""
    if os.path.exists(log_path):
        return
    result = subprocess.run([os.path.join(build, "estimator", "hkf-estimator"), "--source", folder, "--fps", f"{FPS:g}",
                             "--lcm-url", f"file://{log_path}.part?mode=w"], capture_output=True, text=True)
    if result.returncode != 0:
        evaluate.fail(f"hkf-estimator on {folder} exited {result.returncode}: {result.stderr.strip()[-400:]}")
    os.replace(log_path + ".part", log_path)


def retimed(log_path, types_dir, second_late_us=None):
    """The raw log as a live camera at FPS would deliver it (the estimator read the folder faster): each first
    measurement MESH_LATENCY_US after its frame's capture, each second one second_late_us after its frame's
    first (None: as late as in the log, this machine's WHENet lag)."""
    import lcm
    name = "ownlag" if second_late_us is None else f"late{second_late_us // 1000}ms"
    path = log_path.replace(".lcmlog", f".{name}.lcmlog")
    if os.path.exists(path):
        return path
    _, events = read_measurements(log_path, types_dir)
    first_time = {seq: t for t, model, seq, _ in events if model == FIRST}
    capture = {seq: head_pose_utime(data, types_dir) for t, model, seq, data in events if model == FIRST}
    placed = []
    for k, (t, model, seq, data) in enumerate(events):
        arrival = capture.get(seq, head_pose_utime(data, types_dir)) + MESH_LATENCY_US
        if model != FIRST:
            arrival += second_late_us if second_late_us is not None else t - first_time.get(seq, t)
        placed.append((arrival, k, data))
    out = lcm.EventLog(path + ".part", "w", overwrite=True)
    for t, _, data in sorted(placed):
        out.write_event(t, "HEAD_POSE_RAW", data)
    out.close()
    os.replace(path + ".part", path)
    return path


def head_pose_utime(data, types_dir):
    """A raw measurement's capture time (us)."""
    sys.path.insert(0, types_dir)
    from hkf import head_pose_measurement_t
    return head_pose_measurement_t.decode(data).utime


def published(filter_program, log_path, work, settings=()):
    """Every pose hkf-filter --offline publishes, in order: (frame utime, pitch, yaw, roll) rows; settings:
    its --set NAME=VALUE options."""
    os.makedirs(work, exist_ok=True)
    csv_path = os.path.join(work, "hkf.csv")
    command = [filter_program, "--offline", log_path, os.path.join(work, "hkf.lcmlog"), "--csv", csv_path]
    for setting in settings:
        command += ["--set", setting]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        evaluate.fail(f"{' '.join(command)} exited {result.returncode}: {result.stderr.strip()}")
    rows = []
    with open(csv_path) as f:
        for row in csv.DictReader(f):
            if row["status"] == "1" and row["extrapolated"] == "0":
                rows.append((int(row["measurement_utime"]), float(row["pitch"]), float(row["yaw"]), float(row["roll"])))
    return np.array(rows, float).reshape(-1, 4)


class TurnClip:
    """One head turned on one axis: the trajectory, the truth, raw per model per frame, and the raw log
    (per_model: read_measurements' of it)."""

    def __init__(self, head, axis_name, trajectory, log_path, per_model):
        self.head, self.axis_name = head, axis_name
        self.role = "tuning" if head in evaluate.TUNING_CLIPS else "held out"
        self.axis = AXES[axis_name][0]
        self.trajectory, self.log = trajectory, log_path
        first = per_model.get(FIRST, {})
        seqs = sorted(first)[:len(trajectory.theta)]
        self.utime = np.array([first[s][0] for s in seqs], np.int64)
        self.t = trajectory.t[:len(seqs)]
        self.theta = trajectory.theta[:len(seqs)]
        self.raw = {}
        for model in (FIRST, SECOND):
            frames = per_model.get(model, {})
            self.raw[model] = np.array([frames[s][2] if s in frames and frames[s][1] else (np.nan,) * 3 for s in seqs])
        unturned = (self.theta == 0.0) & np.isfinite(self.raw[FIRST][:, 0])
        base_read = np.median(self.raw[FIRST][unturned], axis=0)
        rotations = turns(base_read, self.axis, self.theta)
        self.truth = np.array([truth_clips._angles(r @ truth_clips._rotation(*base_read)) for r in rotations])
        self.moving = np.abs(np.gradient(self.truth[:, self.axis], self.t)) > 10.0
        self.index = {int(u): i for i, u in enumerate(self.utime)}

    @property
    def name(self):
        return f"{self.head}_{self.axis_name}"

    def raw_taken(self):
        """Raw per frame: the mesh where it measures, else WHENet."""
        first, second = self.raw[FIRST], self.raw[SECOND]
        return np.where(np.isfinite(first[:, :1]), first, second)


def reading(clip, model):
    """The model's reading against the turn on the clip's axis, over the settled holds: (slope, residual RMS,
    the widest |truth| it measured)."""
    a = clip.axis
    still = truth_motion.still_mask(truth_motion.Trajectory(clip.t, clip.theta))
    z = clip.raw[model][:, a]
    ok = still & np.isfinite(z)
    if ok.sum() < 10:
        return float("nan"), float("nan"), float("nan")
    x = clip.truth[ok, a]
    slope, offset = np.polyfit(x, z[ok], 1)
    return float(slope), float(np.sqrt(np.mean((z[ok] - slope * x - offset) ** 2))), float(np.max(np.abs(x)))


def holds(clip, rows):
    """Per settled hold: (angle, published still jitter, raw's, the number of published poses)."""
    a, out = clip.axis, []
    frame_of = np.array([clip.index.get(int(u), -1) for u in rows[:, 0]])
    raw = clip.raw_taken()[:, a]
    for name, t0, t1 in clip.trajectory.segments:
        if name != "hold" or t1 - t0 < 0.6:
            continue
        window = (clip.t >= t0 + 0.3) & (clip.t <= t1 + 1e-9)
        in_rows = (frame_of >= 0) & window[np.clip(frame_of, 0, None)]
        p = rows[in_rows, 1 + a]
        r = raw[window]
        r = r[np.isfinite(r)]
        if p.size < 3 or r.size < 3:
            continue
        angle = float(clip.theta[np.flatnonzero(window)[0]])
        out.append((angle, float(np.sqrt(np.mean(np.diff(p) ** 2))), float(np.sqrt(np.mean(np.diff(r) ** 2))), p.size))
    return out


def newest_per_frame(clip, rows):
    """The last pose published for each frame (NaN where none)."""
    out = np.full((len(clip.utime), 3), np.nan)
    for row in rows:
        i = clip.index.get(int(row[0]))
        if i is not None:
            out[i] = row[1:]
    return out


def moving_error(clip, rows):
    """(published RMSE, raw RMSE) on the clip's axis where the truth moves faster than 10 deg/s."""
    a = clip.axis
    newest, raw = newest_per_frame(clip, rows)[:, a], clip.raw_taken()[:, a]
    ok = clip.moving & np.isfinite(newest) & np.isfinite(raw)
    truth = clip.truth[:, a]
    return (float(np.sqrt(np.mean((newest[ok] - truth[ok]) ** 2))), float(np.sqrt(np.mean((raw[ok] - truth[ok]) ** 2))))


def excess_in_fewest(clip, rows, frames=5):
    """The published stream's squared error over raw's on the moving frames, summed (deg^2), and the share of that
    sum the `frames` frames adding most carry: whether a clip's excess is its lag everywhere or a few frames."""
    a = clip.axis
    newest, raw = newest_per_frame(clip, rows)[:, a], clip.raw_taken()[:, a]
    ok = clip.moving & np.isfinite(newest) & np.isfinite(raw)
    excess = (newest[ok] - clip.truth[ok, a]) ** 2 - (raw[ok] - clip.truth[ok, a]) ** 2
    total = float(np.sum(excess))
    fewest = float(np.sum(np.sort(excess)[::-1][:frames]))
    return total, fewest / total if total > 0 else float("nan")


def largest_reversal(clip, rows):
    """Within each move (the truth going one way), the published stream's largest step back against it (deg)."""
    a, worst = clip.axis, 0.0
    frame_of = np.array([clip.index.get(int(u), -1) for u in rows[:, 0]])
    for move in clip.trajectory.moves:
        inside = (frame_of >= 0) & (clip.t[np.clip(frame_of, 0, None)] >= move.t0) & \
                 (clip.t[np.clip(frame_of, 0, None)] <= move.t1 + 1e-9)
        p = np.sign(move.size) * rows[inside, 1 + a]
        if p.size > 1:
            worst = max(worst, float(np.max(np.maximum.accumulate(p) - p)))
    return worst


def largest_handover_step(clip, rows, alone_rows, after_frames=5):
    """Where WHENet starts or stops measuring (frame to frame): over that frame and the after_frames after it (a
    late measurement redoes them), the largest difference between the published pose's step from frame to frame
    (each frame's last pose) and the step of the same filter on the mesh's measurements alone, which has the
    same lag: what the second model's joining or leaving adds."""
    a, worst = clip.axis, 0.0
    has = np.isfinite(clip.raw[SECOND][:, a])
    changes = np.flatnonzero(has[1:] != has[:-1]) + 1
    both, alone = newest_per_frame(clip, rows)[:, a], newest_per_frame(clip, alone_rows)[:, a]
    for i in changes:
        for k in range(max(i, 1), min(i + after_frames + 1, len(both))):
            step = (both[k] - both[k - 1]) - (alone[k] - alone[k - 1])
            if np.isfinite(step):
                worst = max(worst, abs(float(step)))
    return worst


def first_alone(log_path, types_dir):
    """The raw log without the second model's measurements (made once)."""
    import lcm
    path = log_path.replace(".lcmlog", ".first.lcmlog")
    if os.path.exists(path):
        return path
    _, events = read_measurements(log_path, types_dir)
    out = lcm.EventLog(path + ".part", "w", overwrite=True)
    for t, model, _, data in events:
        if model == FIRST:
            out.write_event(t, "HEAD_POSE_RAW", data)
    out.close()
    os.replace(path + ".part", path)
    return path


def make_head(build, out, clip_path):
    index, pose, box = frontal_frame(build, out, clip_path)
    image = truth_clips.read_frames(clip_path, [index])[0]
    points = head_render.landmarks(image, box, os.path.join(evaluate.ROOT, ".models", "face_landmark.onnx"))
    return head_render.Head(image, points), pose


def make_clips(build, out, heads):
    """Every head turned on every axis: TurnClips, rendered and estimated once (reused after)."""
    types_dir = os.path.join(build, "lcmtypes", "python")
    by_name = {os.path.splitext(os.path.basename(c))[0]: c for c in evaluate.clips()}
    made, rendered = [], {}
    for name in heads:
        if name not in by_name:
            evaluate.fail(f"no clip {name} in ../shared/data/videos")
        head, pose = make_head(build, out, by_name[name])
        rendered[name] = (head, pose)
        for axis_name, (axis, reach) in AXES.items():
            seed = sum(map(ord, name + axis_name))
            trajectory = truth_motion.held_turn_trajectory(seed, FPS, max_abs=reach)
            folder = os.path.join(out, "turn", "clips", f"{name}_{axis_name}")
            log_path = folder + ".lcmlog"
            if not os.path.exists(log_path):
                started = time.time()
                if not os.path.isdir(folder):
                    write_clip(folder, head, turns(pose, axis, trajectory.theta), seed)
                estimate(build, folder, log_path)
                log(f"{name} {axis_name}: {len(trajectory.theta)} frames rendered and estimated, "
                    f"{time.time() - started:.0f} s")
            made.append(TurnClip(name, axis_name, trajectory, log_path, read_measurements(log_path, types_dir)[0]))
    return made, rendered


def measure(clips, filters, out):
    """One row per (filter, order, clip)."""
    types_dir = None
    rows = []
    for label, program in filters:
        for order in ORDERS:
            for clip in clips:
                types_dir = types_dir or os.path.join(os.path.dirname(os.path.dirname(program)), "lcmtypes", "python")
                log_path = retimed(clip.log, types_dir, ORDERS[order])
                work = os.path.join(out, "turn", "work", label.replace(" ", "_"), order.replace(" ", "_"), clip.name)
                poses = published(program, log_path, work)
                alone = published(program, first_alone(log_path, types_dir), work)
                hold_rows = holds(clip, poses)
                moving, raw_moving = moving_error(clip, poses)
                rows.append({"filter": label, "order": order, "clip": clip.name, "role": clip.role,
                             "holds": hold_rows, "moving": moving, "raw_moving": raw_moving,
                             "alone_moving": moving_error(clip, alone)[0], "excess": excess_in_fewest(clip, poses),
                             "reversal": largest_reversal(clip, poses), "handover": largest_handover_step(clip, poses, alone),
                             "poses": poses})
    return rows


def hold_summary(hold_rows):
    """(the worst hold's jitter share, its angle, the pooled share)."""
    shares = [(p / r if r > 0 else np.nan, angle) for angle, p, r, _ in hold_rows]
    worst = max(shares, key=lambda s: s[0]) if shares else (np.nan, np.nan)
    pooled = np.sqrt(np.mean([p ** 2 for _, p, _, _ in hold_rows])) / np.sqrt(np.mean([r ** 2 for _, _, r, _ in hold_rows]))
    return worst[0], worst[1], float(pooled)


def reading_table(clips):
    lines = ["### The estimator's reading of the renders (settled holds)", "",
             "| head (axis) | role | mesh slope | mesh residual (deg) | mesh reach (deg) | WHENet slope | "
             "WHENet residual (deg) | WHENet reach (deg) |", "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for clip in clips:
        m, w = reading(clip, FIRST), reading(clip, SECOND)
        lines.append(f"| {clip.name} | {clip.role} | {m[0]:.2f} | {m[1]:.2f} | {m[2]:.0f} | {w[0]:.2f} | {w[1]:.2f} | "
                     f"{w[2]:.0f} |")
    return "\n".join(lines) + "\n"


def excess_cell(excess):
    total, share = excess
    return f"{total:+.0f}, {100 * share:.0f} %" if total > 0 else f"{total:+.0f}"


def results_table(rows):
    lines = ["### Published pose against truth (every pose in the order published)", "",
             f"Goals: every hold's jitter <= {GOALS['hold_jitter_share']:.0%} of raw's, moving RMSE <= "
             f"{GOALS['moving_ratio']:.1f}x raw's, no reversal > {GOALS['reversal_deg']} deg within a move, no step > "
             f"{GOALS['handover_deg']} deg beyond the truth's where WHENet joins or leaves.", "",
             "| filter | order | head (axis) | role | holds: pooled jitter / raw | worst hold (at deg) | "
             "moving RMSE (raw) | x raw | the mesh alone: x raw | excess (deg^2): all, share of the largest 5 frames | "
             "largest reversal (deg) | largest hand-over step (deg) |",
             "| --- | --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for r in rows:
        worst, angle, pooled = hold_summary(r["holds"])
        lines.append(f"| {r['filter']} | {r['order']} | {r['clip']} | {r['role']} | {100 * pooled:.0f} % | "
                     f"{100 * worst:.0f} % ({angle:+.0f}) | {r['moving']:.2f} ({r['raw_moving']:.2f}) | "
                     f"{r['moving'] / r['raw_moving']:.2f} | {r['alone_moving'] / r['raw_moving']:.2f} | "
                     f"{excess_cell(r['excess'])} | {r['reversal']:.2f} | {r['handover']:.2f} |")
    return "\n".join(lines) + "\n"


def contact_sheet(rendered, path):
    """Each head at rest and turned: yaw -40, -20, 20, 40 and pitch -30, 30."""
    import cv2
    turns_shown = [("rest", 0, 0), ("yaw -40", 1, -40), ("yaw -20", 1, -20), ("yaw +20", 1, 20), ("yaw +40", 1, 40),
                   ("pitch -30", 0, -30), ("pitch +30", 0, 30)]
    lines = []
    for name, (head, pose) in rendered.items():
        tiles = []
        for label, axis, angle in turns_shown:
            image = head.render(turns(pose, axis, [angle])[0])
            tile = cv2.resize(image, (200, int(round(200 * image.shape[0] / image.shape[1]))))[:200]
            tile = cv2.copyMakeBorder(tile, 0, 200 - tile.shape[0], 0, 0, cv2.BORDER_CONSTANT)
            cv2.putText(tile, f"{name} {label}", (6, 18), cv2.FONT_HERSHEY_SIMPLEX, 0.5, (0, 255, 0), 1)
            tiles.append(tile)
        lines.append(np.hstack(tiles))
    if not cv2.imwrite(path, np.vstack(lines)):
        evaluate.fail(f"cannot write {path}")


def held_turn_figure(clips, rows, path, head="d10", axis_name="yaw"):
    """A held turn: raw per model, every published pose (this build's, as logged, and the first filter's) and truth."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    clip = next((c for c in clips if c.head == head and c.axis_name == axis_name), clips[0])
    a = clip.axis
    shown = [r for r in rows if r["clip"] == clip.name and r["order"] == "this machine"]
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.5), gridspec_kw={"width_ratios": [2, 1]})
    for ax, (t0, t1) in zip(axes, ((0, clip.t[-1]), (4.0, 9.4))):
        ax.plot(clip.t, clip.truth[:, a], color="black", lw=1.2, label="truth")
        ax.plot(clip.t, clip.raw[FIRST][:, a], ".", ms=3, color="tab:blue", label="raw: face mesh")
        ax.plot(clip.t, clip.raw[SECOND][:, a], ".", ms=3, color="tab:orange", label="raw: WHENet")
        for r, colour in zip(shown, ("tab:red", "tab:green", "tab:purple")):
            poses = r["poses"]
            t = np.array([clip.t[clip.index[int(u)]] if int(u) in clip.index else np.nan for u in poses[:, 0]])
            ax.step(t, poses[:, 1 + a], where="post", color=colour, lw=1, label=f"published: {r['filter']}")
        ax.set_xlim(t0, t1)
        ax.set_xlabel("s")
        ax.set_ylabel(f"{axis_name} (deg)")
    axes[1].set_ylim(15, 55)
    axes[0].legend(fontsize=8, loc="lower left")
    axes[0].set_title(f"{clip.name} ({clip.role}): a staircase of held turns, glances, a drift, a sine")
    axes[1].set_title("holds at 20, 30, 40 deg: every pose published")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(evaluate.ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(evaluate.ROOT, "out", "eval"))
    parser.add_argument("--heads", default=",".join(HEADS), help="clips whose most frontal frame makes a head")
    parser.add_argument("--filter", action="append", default=[], metavar="LABEL=PATH",
                        help="also measure this hkf-filter (e.g. a release's), beside the build's")
    args = parser.parse_args()
    os.makedirs(os.path.join(args.out, "turn"), exist_ok=True)
    clips, rendered = make_clips(args.build, args.out, args.heads.split(","))
    filters = [("this build", os.path.join(args.build, "tools", "hkf-filter"))]
    filters += [tuple(f.split("=", 1)) for f in args.filter]
    rows = measure(clips, filters, args.out)
    folder = os.path.join(args.out, "turn")
    contact_sheet(rendered, os.path.join(folder, "turn_contact.png"))
    held_turn_figure(clips, rows, os.path.join(folder, "turn_hold.png"))
    text = "## Yaw and pitch truth (turn_truth.py)\n\n" + reading_table(clips) + "\n" + results_table(rows)
    with open(os.path.join(folder, "turn.md"), "w") as f:
        f.write(text)
    print(text)
    log(f"wrote {folder}/turn.md, turn_contact.png, turn_hold.png")


if __name__ == "__main__":
    main()
