#!/usr/bin/env python3
"""End to end: what the player feels, against truth.

A truth clip (a real frame turned or zoomed along a known trajectory, with fresh sensor
noise and JPEG on every frame: truth_clips.py) is played as a camera (`--realtime` at
its frame rate) through the real programs, over udpm in a private network namespace:

    hkf-estimator (default pipeline) -> hkf-filter (live) -> hkf-opentrack -> a UDP receiver

The receiver stamps every datagram on arrival with the wall clock, the clock the
estimator stamps its frames with, and lcm-logger records HEAD_POSE_RAW and HEAD_POSE with
their arrival times. The truth of frame i is at capture time t0 + i / fps; between frames it
is interpolated, so each datagram is compared with where the head is when it arrives.

Per variant (the defaults; the paper's settings; raw: hkf-filter with R -> 0, the filter
bypassed; the bridge at 250 Hz with --predict and --lead), and raw in the same run as the defaults: each
measurement as it reaches the node (its HEAD_POSE_RAW message, stamped on arrival by lcm-logger), measured as
if it were a datagram; the shares of raw's jitter are of this raw:
  onset        the first datagram 1 deg toward a move, after the truth shows 1 deg (ms)
  half-move    the first datagram half way, after the truth is half way (ms)
  at arrival   RMS of datagram minus the truth when it arrives, on moving frames (deg)
  overshoot    past the target after a move, as a share of the move
  still jitter RMS frame-to-frame change of what the receiver holds at each frame time, on
               still frames after the start-up hold (deg), and as a share of raw's; the start-up hold is
               the player's rest, whose end moves the centre once (its step is reported as the centre step)
  dropped      frames the estimator dropped, frames without a pose, poses without a datagram
  stages       capture -> raw publish -> pose -> datagram (ms, medians; one datagram per pose)
The lean clip (a zoom: the head nearer and farther) gives the same for the position (TZ, cm). The yaw
and pitch truth (turn_truth.py: a real frame of TURN_HEAD made into a 3D head, turned along a staircase of held
turns, glances, a drift and a sine) run with the default pipeline (both models), at 30 and 60 fps, with the still
jitter per hold too.

Clips: a frontal frame of held-out clips (not the filter's tuning clips, evaluate.TUNING_CLIPS):
--lead's default is chosen on TUNE_CLIP; the report is on REPORT_CLIPS.

usage: e2e.py [--build DIR] [--out DIR] [--short | --turn | --sway]
--sway: only the roll truth whose start-up rest sways 1.2 deg at 0.5 Hz (out/e2e/e2e_sway.md).
--turn: only the yaw and pitch truth (out/e2e/e2e_turn.md, e2e_yaw.png).
--short: one clip of 6 s at 30 fps, the defaults only; exit 1 if no datagram arrives, any is
not finite, or the median onset is beyond SHORT_MAX_ONSET_MS (the ./run test case).
Needs root (a private network namespace: nothing leaves the machine); exit 77 otherwise.
"""
import argparse
import os
import socket
import struct
import subprocess
import sys
import threading
import time
import zlib

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import evaluate  # noqa: E402
import truth_clips  # noqa: E402
import truth_eval  # noqa: E402
import truth_motion  # noqa: E402
import turn_truth  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
URL = "udpm://239.255.76.67:7667?ttl=0"
PORT = 4242
TUNE_CLIP = "d12"
SWAY_DEG, SWAY_HZ, SWAY_S = 1.2, 0.5, 2.0  # --sway: the start-up rest's sway (one whole period, back at 0 at its end)
REPORT_CLIPS = ["d10", "d18"]
TURN_HEAD = "d10"  # the yaw truth's head: held out (the models' curve and the waiting were chosen on d14)
SHORT_MAX_ONSET_MS = 150.0
ROLL, Z = 2, 2
PIVOT_CM = 10.0  # hkf-estimator's --pivot default (estimator/src/models/head_position.hpp): the pivot behind the face
SAMPLE_DELAY_S = 0.04  # still jitter: what the receiver holds this long after each frame's capture
RAW_OPTIONS = ["noise_time=0", "noise_mode=constant", "r_const=0.0001 0.0001 0.0001", "r_min=0.0001",
               "loop_closure=off", "start_rate=0", "process_noise=1000000 1000000 1000000",
               "position_noise_time=0", "position_r_const=0.0001 0.0001 0.0001", "position_start_rate=0",
               "position_process_noise=1000000 1000000 1000000", "position_max_speed=0"]
LEADS_MS = [0, 15, 30]
# The player's rest (the rest issue): the defaults measure it on the clip's 2 s start-up hold; beside them, the
# same without a rest (rest_time 0: the built-in still_wander) and release 0.3's constant wander.
NO_REST = "defaults, no rest (built-in wander)"
RELEASE_03 = "release 0.3 (still_wander 0.3, no rest)"
RELEASE_03_OPTIONS = ["rest_time=0", "still_wander=0.3"]
GOALS = {"onset_ms": 40.0, "onset_max_ms": 60.0, "onset_ms_60": 25.0, "rmse": 0.6, "jitter_share": 0.25,
         "overshoot": 0.05, "dropped_30": 0, "dropped_share_60": 0.01}


def log(message):
    print(f"e2e: {message}", flush=True)


class Variant:
    def __init__(self, name, filter_options=(), bridge_options=(), estimator_options=()):
        self.name, self.filter_options, self.bridge_options = name, list(filter_options), list(bridge_options)
        self.estimator_options = list(estimator_options)


def variants_for(short, lead_ms=None):
    if short:
        return [Variant("defaults")]
    chosen = [] if lead_ms is None else [Variant(f"defaults, 250 Hz, --predict --lead {lead_ms}", (),
                                                 ["--rate", "250", "--predict", "--lead", str(lead_ms)])]
    return [Variant("raw (filter bypassed)", RAW_OPTIONS), Variant("paper settings", evaluate.PAPER_OPTIONS),
            Variant("defaults"), Variant(NO_REST, ["rest_time=0"]), Variant(RELEASE_03, RELEASE_03_OPTIONS),
            Variant("defaults, 250 Hz", (), ["--rate", "250"])] + chosen


# ---- the clips ----

def roll_trajectory(fps, seed):
    """--short's: a hold, then two glances of 15-25 deg at 150-250 deg/s and back."""
    rng = np.random.default_rng(seed)
    b = truth_motion._Builder(fps, rng)
    b.hold(truth_motion.START_REST_S)  # the player's start-up rest
    for _ in range(2):
        home = b.angle
        b.move(home + rng.uniform(15.0, 25.0) * rng.choice([-1.0, 1.0]), rng.uniform(150.0, 250.0), "glance")
        b.hold(0.8)
        b.move(home, rng.uniform(150.0, 250.0), "return")
        b.hold(0.8)
    theta = np.array(b.values)
    return truth_motion.Trajectory(np.arange(len(theta)) / fps, theta, b.moves, b.segments)


def frontal_frame(build, out, clip_name):
    """The clip's most frontal face: (image, face centre, its pose as the estimator reads it)."""
    clip = os.path.join(ROOT, "..", "shared", "data", "videos", clip_name + ".mp4")
    raw = evaluate.raw_log(build, out, clip, "mesh_pnp")
    _, valid, z, centres = truth_eval.read_raw_with_boxes(raw, os.path.join(build, "lcmtypes", "python"))
    found = np.flatnonzero(valid)
    index = int(found[np.argmin(np.abs(z[found, 1]) + np.abs(z[found, 0]))])
    return truth_clips.read_frames(clip, [index])[0], centres[index], z[index]


class Clip:
    def __init__(self, name, folder, fps, kind, theta, scale, moves, roll_of_turn):
        self.name, self.folder, self.fps, self.kind = name, folder, fps, kind
        self.theta, self.scale, self.moves = theta, scale, moves  # per frame; moves: truth_motion.Move
        self.roll_of_turn = roll_of_turn  # the head's roll change for an image turn theta (truth_clips.truth_angles)


def make_clip(out, frame, clip_name, fps, kind, short):
    image, centre, pose = frame
    label = f"{clip_name}_{kind}_{fps:g}fps" + ("_short" if short else "")
    folder = os.path.join(out, "clips", label)
    seed = zlib.crc32(label.encode())
    if kind in ("roll", "roll_sway"):
        trajectory = roll_trajectory(fps, seed) if short else truth_motion.driver_trajectory(seed, fps, glances=4)
        theta, scale, moves = trajectory.theta, np.ones(len(trajectory.theta)), trajectory.moves
        if kind == "roll_sway":  # a player who talks or settles during the start-up rest: a 0.5 Hz sway of 1.2 deg
            t = np.arange(len(theta)) / fps
            theta = theta + np.where(t < SWAY_S, SWAY_DEG * np.sin(2.0 * np.pi * SWAY_HZ * t), 0.0)
    else:  # the lean: a zoom about the face, between holds
        _, scale, _ = truth_motion.lean_trajectory(seed, fps, moves=4)
        scale = np.concatenate([np.ones(int(1.5 * fps)), scale])
        theta = np.zeros(len(scale))
        moves = moves_of(scale, fps)
    if not os.path.exists(os.path.join(folder, f"{len(theta) - 1:05d}.jpg")):
        truth_clips.write_still_clip(folder, image, centre, theta, seed, scale=scale)
        log(f"{label}: {len(theta)} frames written")
    axis = truth_clips.line_of_sight(centre, (image.shape[1], image.shape[0]))

    def roll_of_turn(angles):  # the turn about the line of sight through a face not quite frontal nor centred
        return truth_clips.truth_angles(angles, pose, axis)[:, ROLL] - truth_clips.truth_angles(0.0, pose, axis)[0, ROLL]
    return Clip(label, folder, fps, kind, theta, scale, moves, roll_of_turn)


def make_turn_clip(build, out, fps, axis_name):
    """The yaw or pitch truth (turn_truth.py) for the live chain: TURN_HEAD's most frontal frame made into a 3D
    head and turned along a held-turn trajectory at fps (holds every 10 deg out to turn_truth.AXES' reach,
    glances, a drift, a sine)."""
    head, pose = turn_truth.make_head(build, out, os.path.join(ROOT, "..", "shared", "data", "videos",
                                                               TURN_HEAD + ".mp4"))
    axis, reach = turn_truth.AXES[axis_name]
    label = f"{TURN_HEAD}_{axis_name}_{fps:g}fps"
    folder = os.path.join(out, "clips", label)
    seed = zlib.crc32(label.encode())
    trajectory = truth_motion.held_turn_trajectory(seed, fps, max_abs=reach)
    if not os.path.isdir(folder):
        turn_truth.write_clip(folder, head, turn_truth.turns(pose, axis, trajectory.theta), seed)
        log(f"{label}: {len(trajectory.theta)} frames written")
    clip = Clip(label, folder, fps, "turn", trajectory.theta, np.ones(len(trajectory.theta)), trajectory.moves, None)
    clip.segments = trajectory.segments
    return clip


def moves_of(signal, fps):
    """The moves of a piecewise-held signal: (t0, t1, start, end) of each run of change."""
    changing = np.abs(np.diff(signal)) > 1e-9
    moves, i = [], 0
    while i < len(changing):
        if changing[i]:
            j = i
            while j < len(changing) and changing[j]:
                j += 1
            moves.append(truth_motion.Move(i / fps, j / fps, float(signal[i]), float(signal[j])))
            i = j
        else:
            i += 1
    return moves


# ---- one run of the chain ----

class Receiver(threading.Thread):
    """opentrack's UDP input: every datagram stamped on arrival (wall clock, us)."""

    def __init__(self, port):
        super().__init__(daemon=True)
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.bind(("127.0.0.1", port))
        self.sock.settimeout(0.05)
        self.datagrams, self.stop = [], False

    def run(self):
        while not self.stop:
            try:
                data = self.sock.recv(64)
            except socket.timeout:
                continue
            self.datagrams.append((time.time_ns() // 1000, struct.unpack("<6d", data)))


def run_chain(build, clip, variant, work):
    """The clip through the programs; (datagrams, logger log path, estimator summary)."""
    os.makedirs(work, exist_ok=True)
    log_path = os.path.join(work, "chain.lcmlog")
    if os.path.exists(log_path):
        os.remove(log_path)
    receiver = Receiver(PORT)
    receiver.start()
    logs = {name: open(os.path.join(work, name + ".txt"), "w") for name in ("logger", "filter", "bridge", "estimator")}
    background = [
        subprocess.Popen(["lcm-logger", "-q", "-c", "HEAD_POSE.*", "--lcm-url", URL, log_path],
                         stdout=logs["logger"], stderr=subprocess.STDOUT),
        subprocess.Popen([os.path.join(build, "tools", "hkf-filter"), "--lcm-url", URL]
                         + [a for o in variant.filter_options for a in ("--set", o)],
                         stdout=logs["filter"], stderr=subprocess.STDOUT),
        subprocess.Popen([os.path.join(build, "tools", "hkf-opentrack"), "--lcm-url", URL, "--port", str(PORT)]
                         + variant.bridge_options, stdout=logs["bridge"], stderr=subprocess.STDOUT)]
    evaluate.wait_started([(background[1], logs["filter"]), (background[2], logs["bridge"])])  # before frame 1
    estimator = subprocess.run([os.path.join(build, "estimator", "hkf-estimator"), "--source", clip.folder,
                                "--fps", f"{clip.fps:g}", "--realtime", "--lcm-url", URL] + variant.estimator_options,
                               stdout=subprocess.PIPE, stderr=logs["estimator"], text=True)
    time.sleep(0.5)
    for proc in reversed(background):
        proc.send_signal(2)
        proc.wait(timeout=10)
    receiver.stop = True
    receiver.join()
    receiver.sock.close()
    for f in logs.values():
        f.close()
    if estimator.returncode != 0:
        evaluate.fail(f"hkf-estimator on {clip.folder} exited {estimator.returncode} (see {work}/estimator.txt)")
    return receiver.datagrams, log_path, estimator.stdout


def decoded_events(path, types_dir):
    """(arrival us, channel, decoded message) of each HEAD_POSE_RAW and HEAD_POSE event of a logger's log."""
    import lcm
    sys.path.insert(0, types_dir)
    from hkf import head_pose_measurement_t, head_pose_t
    types = {"HEAD_POSE_RAW": head_pose_measurement_t, "HEAD_POSE": head_pose_t}
    for event in lcm.EventLog(path, "r"):
        if event.channel in types:
            yield event.timestamp, event.channel, types[event.channel].decode(event.data)


def read_chain_log(path, types_dir):
    """The first model's raw measurements and the published poses, with their arrival times (us)."""
    raw, poses = [], []
    for timestamp, channel, m in decoded_events(path, types_dir):
        if channel == "HEAD_POSE_RAW" and m.model == "mesh_pnp":
            raw.append((timestamp, m.utime, m.seq, m.valid, m.roll, m.z, m.yaw, m.pitch))
        elif channel == "HEAD_POSE":
            poses.append((timestamp, m.utime, m.measurement_utime, m.extrapolated))
    return np.array(raw, float), np.array(poses, float)


# ---- the measures ----

class Truth:
    """The truth as a function of wall-clock time (us): frame i at t0 + i / fps, linear between."""

    def __init__(self, t0_us, fps, values):
        self.t = t0_us + np.arange(len(values)) * 1e6 / fps
        self.values = np.asarray(values, float)

    def at(self, t_us):
        return np.interp(t_us, self.t, self.values, left=self.values[0], right=self.values[-1])

    def speed(self, t_us):
        return np.interp(t_us, self.t, np.abs(np.gradient(self.values, self.t / 1e6)))


def first_crossing(times, values, start_us, level, direction):
    """The first time at or after start_us at which direction * values reaches direction * level."""
    after = np.flatnonzero((times >= start_us) & (direction * values >= direction * level))
    return float(times[after[0]]) if after.size else float("nan")


def still_jitter(clip, truth, arrival, value, hold_end_us):
    """(still jitter, the largest step during the start-up hold): what the receiver holds SAMPLE_DELAY_S after
    each frame's capture, frame to frame, over still frames after the hold."""
    frame_t = truth.t + SAMPLE_DELAY_S * 1e6
    held_index = np.searchsorted(arrival, frame_t, side="right") - 1
    held = np.where(held_index >= 0, value[np.clip(held_index, 0, None)], np.nan)
    # a sample SAMPLE_DELAY_S after frame i's capture may already hold frame i + 1's pose (captured one frame
    # period later and sent within the rest): a pair counts only when the frame after it is still too
    still = still_frames(truth.values, clip.fps)
    still[:-1] &= still[1:]
    # the start-up hold is the player's rest, at whose end the centre moves onto the rest's mean (once, as a
    # recentre does): still frames are counted after it; the step the centre made is reported on its own
    in_hold = truth.t < hold_end_us
    centre_step = float(np.nanmax(np.abs(np.diff(held[in_hold])))) if in_hold.sum() > 1 else np.nan
    still &= ~in_hold
    steps = np.diff(held)
    pairs = still[1:] & still[:-1] & np.isfinite(steps)
    jitter = float(np.sqrt(np.mean(steps[pairs] ** 2))) if pairs.any() else np.nan
    return jitter, centre_step


def measure_run(clip, datagrams, raw, poses, estimator_summary, player_axis, scale_to_truth):
    """The measures of one run; player_axis picks what the player sees from a datagram."""
    arrival = np.array([d[0] for d in datagrams], float)
    value = np.array([player_axis(d[1]) for d in datagrams], float)
    frame0 = raw[raw[:, 2] == raw[:, 2].min()][0]
    t0 = frame0[1] - frame0[2] * 1e6 / clip.fps  # the capture stamp of frame 0
    truth = Truth(t0, clip.fps, scale_to_truth(clip))
    # the player's zero: the end of the initial hold, after the start-up rest has set the centre (its mean pose)
    values = scale_to_truth(clip)
    moved = np.flatnonzero(np.abs(values - values[0]) > 1e-9)
    hold_end_us = t0 + (moved[0] / clip.fps if moved.size else 1.4) * 1e6
    hold = (arrival > hold_end_us - 0.4e6) & (arrival < hold_end_us - 0.05e6)
    value = value - (np.median(value[hold]) if hold.any() else 0.0)
    moving = truth.speed(arrival) > (10.0 if clip.kind in ("roll", "turn") else 2.0)
    at_arrival = float(np.sqrt(np.mean((value[moving] - truth.at(arrival[moving])) ** 2))) if moving.any() else np.nan
    onsets, halves, overshoots = [], [], []
    threshold = 1.0  # deg, or cm for the lean
    for k, move in enumerate(clip.moves):
        start, end = truth.at(t0 + move.t0 * 1e6), truth.at(t0 + move.t1 * 1e6)
        size, direction = abs(end - start), np.sign(end - start)
        if size < 2 * threshold:
            continue
        m0, m1 = t0 + move.t0 * 1e6, t0 + move.t1 * 1e6
        before = (arrival > m0 - 0.3e6) & (arrival <= m0)
        base = float(np.median(value[before])) if before.any() else float(start)
        fine = np.linspace(m0, m1, 400)
        t_truth = first_crossing(fine, truth.at(fine), m0, start + direction * threshold, direction)
        t_out = first_crossing(arrival, value, m0, base + direction * threshold, direction)
        h_truth = first_crossing(fine, truth.at(fine), m0, start + direction * size / 2, direction)
        h_out = first_crossing(arrival, value, m0, base + direction * size / 2, direction)
        onsets.append((t_out - t_truth) / 1000.0)
        halves.append((h_out - h_truth) / 1000.0)
        window_end = t0 + (clip.moves[k + 1].t0 if k + 1 < len(clip.moves) else move.t1 + 1.5) * 1e6
        after = (arrival > m1) & (arrival < min(window_end, m1 + 1.5e6))
        beyond = direction * (value[after] - end)
        overshoots.append(max(0.0, float(beyond.max())) / size if after.any() else np.nan)
    jitter, centre_step = still_jitter(clip, truth, arrival, value, hold_end_us)
    dropped = parse_dropped(estimator_summary)
    frames = len(clip.theta)
    measured = np.unique(raw[:, 1])
    posed = set(poses[poses[:, 3] == 0, 2].astype(np.int64)) if len(poses) else set()
    without_pose = int(sum(1 for u in measured.astype(np.int64) if u not in posed))
    return {"onset": np.array(onsets), "half": np.array(halves), "at_arrival": at_arrival,
            "overshoot": np.array(overshoots), "jitter": jitter, "frames": frames, "raw_frames": len(measured),
            "dropped": dropped + (frames - len(measured)), "without_pose": without_pose,
            "datagrams": len(datagrams), "poses": len(poses), "finite": bool(np.isfinite(value).all()),
            "arrival": arrival, "value": value, "truth": truth, "t0": t0, "centre_step": centre_step}


def hold_jitters(clip, m, settle_s=0.3):
    """Per hold of a turn clip (clip.segments) of at least 2 settle_s after the start-up rest (whose end moves the
    centre: still_jitter): (the angle, the still jitter of what the receiver holds SAMPLE_DELAY_S after each
    frame's capture, frame to frame, from settle_s into the hold)."""
    truth = m["truth"]
    held_index = np.searchsorted(m["arrival"], truth.t + SAMPLE_DELAY_S * 1e6, side="right") - 1
    held = np.where(held_index >= 0, m["value"][np.clip(held_index, 0, None)], np.nan)
    out = []
    for name, t0, t1 in clip.segments:
        first, last = int(np.ceil((t0 + settle_s) * clip.fps)), int(np.floor(t1 * clip.fps))
        if name != "hold" or t0 <= 0.0 or t1 - t0 < 2 * settle_s or last - first < 3:  # t0 0: the start-up rest
            continue
        steps = np.diff(held[first:last])  # frame i's sample to frame i + 1's, both in the hold
        steps = steps[np.isfinite(steps)]
        if steps.size >= 3:
            out.append((float(clip.theta[first]), float(np.sqrt(np.mean(steps ** 2)))))
    return out


def hold_lines(named):
    """The defaults' still jitter per hold against raw's from the same run."""
    mine, raw = hold_jitters(named["defaults"]["clip"], named["defaults"]), hold_jitters(
        named[SAME_RUN_RAW]["clip"], named[SAME_RUN_RAW])
    shares = [(angle, p / r) for (angle, p), (_, r) in zip(mine, raw) if r > 0]
    worst = max(shares, key=lambda x: x[1]) if shares else (np.nan, np.nan)
    return ["- defaults, still jitter per hold as a share of raw's (goal <= 10 % at every hold): " +
            ", ".join(f"{angle:+.0f} deg {100 * share:.0f} %" for angle, share in shares) +
            f"; worst {100 * worst[1]:.0f} % at {worst[0]:+.0f} deg ({'met' if worst[1] <= 0.1 else 'NOT met'})"]


def still_frames(values, fps, settle_s=0.3):
    still = np.zeros(len(values), dtype=bool)
    run = 0
    for i in range(len(values)):
        run = run + 1 if i > 0 and abs(values[i] - values[i - 1]) < 1e-9 else 0
        still[i] = run >= settle_s * fps
    return still


def parse_dropped(summary):
    for line in summary.splitlines():
        if " dropped;" in line:
            return int(line.split(" dropped;")[0].rsplit(" ", 1)[1])
    return 0


def stages(raw, poses, datagrams):
    """Medians (ms) of capture -> raw publish -> pose -> datagram, one datagram per pose."""
    capture_to_raw = (raw[:, 0] - raw[:, 1]) / 1000.0
    raw_arrival = {int(u): t for t, u in zip(raw[:, 0], raw[:, 1])}
    measured = poses[poses[:, 3] == 0]
    raw_to_pose = [(p[0] - raw_arrival[int(p[2])]) / 1000.0 for p in measured if int(p[2]) in raw_arrival]
    n = min(len(poses), len(datagrams))
    pose_to_datagram = [(datagrams[k][0] - poses[k, 0]) / 1000.0 for k in range(n)] if len(datagrams) == len(poses) else []
    return [float(np.median(x)) if len(x) else np.nan for x in (capture_to_raw, raw_to_pose, pose_to_datagram)]


def roll_truth(clip):
    return clip.roll_of_turn(clip.theta)


def roll_of_datagram(values):
    return -values[5]  # opentrack's roll is hkf's with the sign flipped


def yaw_of_datagram(values):
    return values[3]  # opentrack's yaw is hkf's


def pitch_of_datagram(values):
    return values[4]  # opentrack's pitch is hkf's


def turn_truth_of(clip):
    """The head's yaw or pitch change: R(b + d) R(b)^T turns the head at b to b + d in hkf's angles
    (turn_truth.turns)."""
    return clip.theta


def tz_of_datagram(values):
    return values[2]  # TZ: hkf's z from the centre position, cm


# ---- the report ----

def row_text(name, m, raw_jitter):
    share = m["jitter"] / raw_jitter if raw_jitter and np.isfinite(raw_jitter) else np.nan
    unsent = f"{m['poses'] - m['datagrams']}" if m["poses"] >= m["datagrams"] else "-"  # -: not one datagram per pose
    lost = f"{m['dropped']} / {m['without_pose']} / {unsent}"
    return (f"| {name} | {np.nanmedian(m['onset']):.0f} | {np.nanmax(m['onset']):.0f} | {np.nanmedian(m['half']):.0f} | "
            f"{m['at_arrival']:.2f} | {100 * np.nanmax(m['overshoot']):.1f} % | {m['jitter']:.3f} ({100 * share:.0f} %) | "
            f"{lost} | {m['datagrams']} |")


HEADER = ("| variant | onset median (ms) | onset worst (ms) | half-move median (ms) | RMSE at arrival, moving | "
          "overshoot, worst | still jitter (share of raw) | frames dropped / without a pose / poses not sent | datagrams |\n"
          "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")


def plot(path, runs, title, quantity="roll, deg (as the player sees it)", from_farthest=False):
    """The first two moves of over 5 deg (from_farthest: the two that start farthest from 0), each run's
    datagrams against the truth."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.2))
    base = runs[0][1]
    moves = [m for m in base["clip"].moves if abs(m.end_angle - m.start_angle) > 5]
    if from_farthest:
        moves = sorted(sorted(moves, key=lambda m: -abs(m.start_angle))[:2], key=lambda m: m.t0)
    moves = moves[:2]
    for ax, move in zip(axes, moves):
        t0 = base["t0"]
        lo, hi = t0 + (move.t0 - 0.25) * 1e6, t0 + (move.t1 + 0.35) * 1e6
        fine = np.linspace(lo, hi, 500)
        ax.plot((fine - lo) / 1000.0, base["truth"].at(fine), "k-", lw=2, label="truth")
        for name, m in runs:  # each run on its own clock: the same window of its clip
            run_lo = m["t0"] + (move.t0 - 0.25) * 1e6
            keep = (m["arrival"] >= run_lo) & (m["arrival"] <= run_lo + (hi - lo))
            ax.step((m["arrival"][keep] - run_lo) / 1000.0, m["value"][keep], where="post", label=name, lw=1.2)
        ax.set_xlabel("ms (datagram arrival)")
        ax.set_ylabel(quantity)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


SAME_RUN_RAW = "raw, as it reaches the node (the defaults' run)"


def raw_as_datagrams(raw):
    """The valid raw measurements of a run as the receiver would hold them: (arrival, the six values), with
    roll, yaw and z where roll_of_datagram, yaw_of_datagram and tz_of_datagram read them."""
    valid = raw[raw[:, 3] != 0]
    return [(t, (0.0, 0.0, z, yaw, pitch, -roll)) for t, roll, z, yaw, pitch in
            zip(valid[:, 0], valid[:, 4], valid[:, 5], valid[:, 6], valid[:, 7])]


def run_clip(build, out, clip, variants, axis, to_truth):
    """Each variant through the chain; after the defaults, raw from the same run (SAME_RUN_RAW)."""
    results = []
    for variant in variants:
        work = os.path.join(out, "runs", clip.name, variant.name.replace(" ", "_").replace(",", "").replace("(", "")
                            .replace(")", ""))
        started = time.time()
        datagrams, log_path, summary = run_chain(build, clip, variant, work)
        raw, poses = read_chain_log(log_path, os.path.join(build, "lcmtypes", "python"))
        m = measure_run(clip, datagrams, raw, poses, summary, axis, to_truth)
        m["stages"] = stages(raw, poses, datagrams) if "--rate" not in variant.bridge_options else [np.nan] * 3
        m["clip"] = clip
        log(f"{clip.name}: {variant.name}: {len(datagrams)} datagrams, onset median {np.nanmedian(m['onset']):.0f} ms, "
            f"at arrival {m['at_arrival']:.2f}, {time.time() - started:.0f} s")
        results.append((variant.name, m))
        if variant.name == "defaults":
            same = measure_run(clip, raw_as_datagrams(raw), raw, poses, summary, axis, to_truth)
            same["stages"], same["clip"] = [np.nan] * 3, clip
            same["poses"] = 0  # not one datagram per pose: its row shows "-"
            results.append((SAME_RUN_RAW, same))
    return results


def raw_jitter_of(runs):
    """The denominator of the jitter shares: the same run's raw where there is one, else the bypass variant's."""
    named = dict(runs)
    return (named.get(SAME_RUN_RAW) or named.get("raw (filter bypassed)") or runs[0][1])["jitter"]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(ROOT, "out", "e2e"))
    parser.add_argument("--short", action="store_true")
    parser.add_argument("--turn", action="store_true", help="only the yaw and pitch truth (both models), 30 and 60 fps")
    parser.add_argument("--sway", action="store_true",
                        help="only the roll truth with a start-up rest in which the head sways 1.2 deg at 0.5 Hz")
    args = parser.parse_args()
    if os.environ.get("HKF_IN_NETNS") != "1":
        os.environ["HKF_IN_NETNS"] = "1"
        os.execv(os.path.join(ROOT, "tools", "lcm-netns"), [os.path.join(ROOT, "tools", "lcm-netns"), sys.executable,
                                                            os.path.abspath(__file__)] + sys.argv[1:])
    build, out = os.path.abspath(args.build), os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    if args.short:
        return short_case(build, out)
    if args.turn:
        return turn_only(build, out)
    if args.sway:
        return sway_only(build, out)
    return full_report(build, out)


def sway_only(build, out):
    """--sway: the held-out roll truth with a swaying start-up rest (out/e2e/e2e_sway.md): the defaults (the rest
    refused, asked again) and the built-in wander, against raw in the same run."""
    lines = ["# End to end: a start-up rest in which the head sways", "",
             f"Made by `./run e2e` (dev/eval/e2e.py --sway): the roll truth clips with their start-up hold made a "
             f"{SWAY_HZ:g} Hz sway of {SWAY_DEG:g} deg for {SWAY_S:g} s (a player who talks or settles during the "
             "countdown), through the live chain.", ""]
    for clip_name in REPORT_CLIPS:
        frame = frontal_frame(build, out, clip_name)
        for fps in (30.0, 60.0):
            clip = make_clip(out, frame, clip_name, fps, "roll_sway", short=False)
            runs = run_clip(build, out, clip, [Variant("defaults"), Variant(NO_REST, ["rest_time=0"])],
                            roll_of_datagram, roll_truth)
            raw_jitter = raw_jitter_of(runs)
            lines += [f"## {clip.name} (held out): roll, the start-up rest swaying", "", HEADER]
            lines += [row_text(n, m, raw_jitter) for n, m in runs] + [""] + goal_lines(dict(runs)) + [""]
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out, "e2e_sway.md"), "w") as f:
        f.write(text)
    print(text)
    log(f"table in {out}/e2e_sway.md")
    return 0


def short_case(build, out):
    clip = make_clip(out, frontal_frame(build, out, REPORT_CLIPS[0]), REPORT_CLIPS[0], 30.0, "roll", short=True)
    named = dict(run_clip(build, out, clip, variants_for(True), roll_of_datagram, roll_truth))
    m, raw = named["defaults"], named[SAME_RUN_RAW]
    problems = []
    if m["datagrams"] == 0:
        problems.append("no datagram arrived")
    if not m["finite"]:
        problems.append("a datagram is not finite")
    if not np.nanmedian(m["onset"]) <= SHORT_MAX_ONSET_MS:
        problems.append(f"the median onset is {np.nanmedian(m['onset']):.0f} ms (at most {SHORT_MAX_ONSET_MS:.0f})")
    log(f"short: {m['datagrams']} datagrams for {m['frames']} frames; onset median {np.nanmedian(m['onset']):.0f} ms, "
        f"worst {np.nanmax(m['onset']):.0f} ms; half-move {np.nanmedian(m['half']):.0f} ms; at arrival "
        f"{m['at_arrival']:.2f} deg; stages {', '.join(f'{s:.1f}' for s in stages_or_nan(m))} ms; raw in the same run: "
        f"onset median {np.nanmedian(raw['onset']):.0f} ms, worst {np.nanmax(raw['onset']):.0f} ms, at arrival "
        f"{raw['at_arrival']:.2f} deg")
    for problem in problems:
        log(f"FAIL: {problem}")
    return 1 if problems else 0


def goal_lines(named):
    """The rest issue's end-to-end goals for the defaults (the start-up rest measured), against raw from the
    same run; and, for comparison, the same figures without a rest and with release 0.3's wander."""
    raw = named[SAME_RUN_RAW]
    raw_onset = (np.nanmedian(raw["onset"]), np.nanmax(raw["onset"]))
    lines = []
    for name in ("defaults", NO_REST, RELEASE_03):
        mine = named.get(name)
        if mine is None:
            continue
        onset = (np.nanmedian(mine["onset"]), np.nanmax(mine["onset"]))
        checks = [("onset median <= raw's + 5 ms, worst <= raw's + 10 ms",
                   f"{onset[0]:.0f} / {onset[1]:.0f} ms against {raw_onset[0]:.0f} / {raw_onset[1]:.0f} ms",
                   onset[0] <= raw_onset[0] + 5.0 and onset[1] <= raw_onset[1] + 10.0),
                  ("RMSE at arrival, moving, <= 1.0x raw's (stretch 0.8x)",
                   f"{mine['at_arrival'] / raw['at_arrival']:.2f}x", mine["at_arrival"] <= raw["at_arrival"]),
                  ("still jitter <= 10 % of raw's", f"{100 * mine['jitter'] / raw['jitter']:.0f} %",
                   mine["jitter"] <= 0.1 * raw["jitter"]),
                  ("overshoot <= 5 % of the move", f"{100 * np.nanmax(mine['overshoot']):.1f} %",
                   np.nanmax(mine["overshoot"]) <= 0.05)]
        lines += [f"- {name}, {what}: {value} ({'met' if ok else 'NOT met'})" for what, value, ok in checks]
        lines.append(f"- {name}: the largest step during the start-up hold (the centre set by the rest): "
                     f"{mine['centre_step']:.2f} deg")
    return lines


def stages_or_nan(m):
    return m.get("stages", [np.nan] * 3)


def full_report(build, out):
    lines = ["# End to end: the live chain against truth", "",
             "Made by `./run e2e` (dev/eval/e2e.py): truth clips played as a camera (`--realtime`) through "
             "hkf-estimator -> hkf-filter -> hkf-opentrack -> a UDP receiver, in a private network namespace.", ""]
    # --lead: chosen on the tuning clip, the least RMSE at arrival whose still jitter is within the goal
    tune = make_clip(out, frontal_frame(build, out, TUNE_CLIP), TUNE_CLIP, 30.0, "roll", short=False)
    tuning = run_clip(build, out, tune, [Variant("raw (filter bypassed)", RAW_OPTIONS)] +
                      [Variant(f"defaults, 250 Hz, --predict --lead {lead}", (),
                               ["--rate", "250", "--predict", "--lead", str(lead)]) for lead in LEADS_MS] +
                      [Variant("defaults, 250 Hz", (), ["--rate", "250"])], roll_of_datagram, roll_truth)
    raw_jitter, plain = tuning[0][1]["jitter"], tuning[-1][1]
    # a lead counts when it cuts the error at arrival by at least 10 % against the same stream without
    # prediction, without more than 10 % more jitter or overshoot
    candidates = [(m["at_arrival"], lead) for lead, (_, m) in zip(LEADS_MS, tuning[1:1 + len(LEADS_MS)])
                  if m["at_arrival"] <= 0.9 * plain["at_arrival"] and m["jitter"] <= 1.1 * plain["jitter"]
                  and np.nanmax(m["overshoot"]) <= 1.1 * np.nanmax(plain["overshoot"]) + 0.005]
    lead = min(candidates)[1] if candidates else None
    lines += [f"## --predict and --lead, on {tune.name} (tuning)", "", HEADER]
    lines += [row_text(name, m, raw_jitter) for name, m in tuning]
    lines += ["", f"Chosen: --predict --lead {lead} ms (the least error at arrival among those that cut it by 10 % "
                  "without 10 % more jitter or overshoot)." if lead is not None else
              "Chosen: no prediction (the default): no lead cut the error at arrival by 10 % against the same "
              "250 Hz stream without prediction. The report's clips show --predict --lead 0 beside it.", ""]
    lead = 0 if lead is None else lead
    stage_rows = []
    for clip_name in REPORT_CLIPS:
        frame = frontal_frame(build, out, clip_name)
        for fps in (30.0, 60.0):
            clip = make_clip(out, frame, clip_name, fps, "roll", short=False)
            runs = run_clip(build, out, clip, variants_for(False, lead), roll_of_datagram, roll_truth)
            raw_jitter = raw_jitter_of(runs)
            lines += [f"## {clip.name} (held out): roll", "", HEADER] + [row_text(n, m, raw_jitter) for n, m in runs] + [""]
            lines += goal_lines(dict(runs)) + [""]
            stage_rows += [f"| {clip.name} | {n} | " + " | ".join(f"{s:.1f}" for s in m["stages"]) + " |"
                           for n, m in runs if np.isfinite(m["stages"]).all()]
            if clip_name == REPORT_CLIPS[0] and fps == 30.0:
                shown = [r for r in runs if r[0] in (SAME_RUN_RAW, "defaults") or "--predict" in r[0]]
                plot(os.path.join(out, "e2e_roll.png"), shown, f"{clip.name}: truth and the datagrams as they arrive")
        lean = make_clip(out, frame, clip_name, 30.0, "lean", short=False)
        runs = run_clip(build, out, lean, [Variant("raw (filter bypassed)", RAW_OPTIONS), Variant("defaults")],
                        tz_of_datagram, lambda c: lean_truth_cm(build, out, c))
        raw_jitter = raw_jitter_of(runs)
        lines += [f"## {lean.name} (held out): position TZ, cm", "", HEADER.replace("deg", "cm")]
        lines += [row_text(n, m, raw_jitter) for n, m in runs] + [""]
    lines += turn_report(build, out)
    lines += ["## Where the time goes (medians, ms; one datagram per pose)", "",
              "| clip | variant | capture -> raw publish | raw -> pose | pose -> datagram |", "| --- | --- | ---: | ---: | ---: |"]
    lines += stage_rows
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out, "e2e.md"), "w") as f:
        f.write(text)
    print(text)
    log(f"table in {out}/e2e.md, pictures in {out}/e2e_roll.png, {out}/e2e_yaw.png")
    return 0


def turn_report(build, out):
    """The yaw and pitch truth through the live chain (both models, the default pipeline), at 30 and 60 fps: the
    table, the goals, the still jitter per hold; the 30 fps yaw run drawn (e2e_yaw.png)."""
    lines = []
    for axis_name, datagram_axis in (("yaw", yaw_of_datagram), ("pitch", pitch_of_datagram)):
        for fps in (30.0, 60.0):
            clip = make_turn_clip(build, out, fps, axis_name)
            runs = run_clip(build, out, clip, [Variant("raw (filter bypassed)", RAW_OPTIONS), Variant("defaults")],
                            datagram_axis, turn_truth_of)
            named = dict(runs)
            lines += [f"## {clip.name} (held out): {axis_name}, the default pipeline (both models)", "", HEADER]
            lines += [row_text(n, m, raw_jitter_of(runs)) for n, m in runs] + [""]
            lines += goal_lines(named) + hold_lines(named) + [""]
            if fps == 30.0 and axis_name == "yaw":
                plot(os.path.join(out, "e2e_yaw.png"), [r for r in runs if r[0] in (SAME_RUN_RAW, "defaults")],
                     f"{clip.name}: the moves from the largest held turns (where the mesh waits for WHENet)",
                     "yaw, deg (as the player sees it)",
                     from_farthest=True)
    return lines


def turn_only(build, out):
    """--turn: only the yaw and pitch truth (out/e2e/e2e_turn.md)."""
    text = "\n".join(["# End to end: the yaw and pitch truth through the live chain", ""] +
                      turn_report(build, out)) + "\n"
    with open(os.path.join(out, "e2e_turn.md"), "w") as f:
        f.write(text)
    print(text)
    log(f"table in {out}/e2e_turn.md, picture in {out}/e2e_yaw.png")
    return 0


_lean_z = {}


def lean_truth_cm(build, out, clip):
    """TZ truth (cm, from the initial hold) of a lean clip: the image zoomed by s about the face is the
    face at distance d / s, d its distance at zoom 1 - the pivot's z (the raw median over the first hold,
    measured once offline) less PIVOT_CM, which a zoom does not scale."""
    if clip.name not in _lean_z:
        log_path = os.path.join(out, "clips", clip.name + ".z.lcmlog")
        if not os.path.exists(log_path):
            truth_eval.FPS = clip.fps
            truth_eval.estimate_folder(build, clip.folder, log_path)
        import lcm
        sys.path.insert(0, os.path.join(build, "lcmtypes", "python"))
        from hkf import head_pose_measurement_t
        zs = [head_pose_measurement_t.decode(e.data) for e in lcm.EventLog(log_path, "r") if e.channel == "HEAD_POSE_RAW"]
        z_hold = [m.z for m in zs if m.seq < int(1.4 * clip.fps) and m.z > 0]
        _lean_z[clip.name] = float(np.median(z_hold))
    face = _lean_z[clip.name] - PIVOT_CM  # the face's distance: the zoom scales it, not the pivot behind it
    return face / clip.scale - face


if __name__ == "__main__":
    sys.exit(main())
