#!/usr/bin/env python3
"""hkf-track: the whole live tracker in one command. Starts hkf-estimator
(camera or video -> HEAD_POSE_RAW), hkf-filter (-> HEAD_POSE) and, with
--opentrack, hkf-opentrack (-> opentrack's "UDP over network" input); prints
the camera and filter rates, the capture-to-pose latency and the head pose once
a second; stops them all on Ctrl-C (or when a video ends) and prints their
summaries. Each program's messages go to a log in --logs.

  ./run track --camera 0 --opentrack          a webcam into opentrack
  ./run track --source clip.mp4 --realtime    a video standing in for the camera
"""
import argparse
import collections
import ctypes
import os
import re
import select
import shlex
import signal
import subprocess
import sys
import time

import lcm

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
DEFAULT_URL = "udpm://239.255.76.67:7667?ttl=0"
STATUS = {1: "TRACKING", 2: "COASTING", 3: "LOST"}


def installed():
    """True for an installed hkf-track (cmake --install): the programs beside it."""
    return os.access(os.path.join(HERE, "hkf-filter"), os.X_OK)


def read_version():
    """The VERSION file: the source tree's, or the one installed in share/hkf."""
    for path in (os.path.join(ROOT, "VERSION"), os.path.join(HERE, os.pardir, "share", "hkf", "VERSION")):
        if os.path.exists(path):
            with open(path) as f:
                return f.read().strip()
    return "unknown"


def parse_args():
    p = argparse.ArgumentParser(prog="hkf-track", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--version", action="version", version=f"hkf-track {read_version()}")
    src = p.add_mutually_exclusive_group(required=True)
    src.add_argument("--camera", metavar="N", help="camera index (0) or device (/dev/video0)")
    src.add_argument("--source", metavar="FILE", help="a video file or a folder of images instead of a camera")
    p.add_argument("--realtime", action="store_true", help="pace a file at its frame rate, like a camera")
    p.add_argument("--model", help="head-pose model for hkf-estimator (mesh_pnp, whenet)")
    p.add_argument("--detector", choices=["retina", "short", "full"],
                   help="hkf-estimator's face search (default retina: near, far and turned faces)")
    p.add_argument("--second-model", metavar="NAME",
                   help="the model hkf-estimator runs beside the first at large turns (default whenet; none: the "
                        "first alone); hkf-filter fuses both")
    p.add_argument("--config", metavar="FILE", help="hkf-filter settings file")
    p.add_argument("--rate", type=float, metavar="HZ", help="hkf-filter also publishes extrapolated poses at HZ")
    p.add_argument("--opentrack", action="store_true", help="also run hkf-opentrack")
    p.add_argument("--opentrack-host", default="127.0.0.1")
    p.add_argument("--opentrack-port", default="4242")
    p.add_argument("--opentrack-args", default="", help="more hkf-opentrack options, e.g. '--invert yaw'")
    p.add_argument("--lcm-url", default=DEFAULT_URL, help=f"LCM provider for all of them (default {DEFAULT_URL})")
    p.add_argument("--seconds", type=float, default=0.0, help="stop after this long (default: Ctrl-C)")
    p.add_argument("--build", default=None,
                   help="where the programs were built (default: installed beside hkf-track, else ./build)")
    p.add_argument("--logs", default=None,
                   help="folder for the programs' logs (default out/track in the source tree, or ./hkf-track-logs)")
    args = p.parse_args()
    if args.logs is None:
        args.logs = os.path.join(os.getcwd(), "hkf-track-logs") if installed() else os.path.join(ROOT, "out", "track")
    if args.source is not None and not os.path.exists(args.source):
        p.error(f"--source: no such file or folder: {args.source}")
    if args.rate is not None and not 0.0 < args.rate <= 10000.0:
        p.error("--rate wants a frequency above 0 and up to 10000 Hz")
    if args.seconds < 0:
        p.error("--seconds wants a duration >= 0")
    return args


def layout(args):
    """(folder of hkf-filter and hkf-opentrack, of hkf-estimator, of the Python message types): the
    build tree (--build, or ./build), or, for an installed hkf-track, its own bin and share/hkf."""
    if args.build is None and installed():
        return HERE, HERE, os.path.join(HERE, os.pardir, "share", "hkf", "python")
    build = args.build or os.path.join(ROOT, "build")
    return os.path.join(build, "tools"), os.path.join(build, "estimator"), os.path.join(build, "lcmtypes", "python")


def commands(args):
    """(name, argv) of each program, in start order: the consumers first, so no pose is missed."""
    (tools, estimator, _), url = layout(args), args.lcm_url
    out = []
    if args.opentrack:
        out.append(("hkf-opentrack", [os.path.join(tools, "hkf-opentrack"), "--lcm-url", url, "--host",
                                      args.opentrack_host, "--port", args.opentrack_port,
                                      *shlex.split(args.opentrack_args)]))
    flt = [os.path.join(tools, "hkf-filter"), "--lcm-url", url]
    if args.config:
        flt += ["--config", args.config]
    if args.rate:
        flt += ["--rate", str(args.rate)]
    out.append(("hkf-filter", flt))
    est = [os.path.join(estimator, "hkf-estimator"), "--source",
           args.camera if args.camera is not None else args.source, "--lcm-url", url]
    if args.realtime:
        est.append("--realtime")
    if args.model:
        est += ["--model", args.model]
    if args.detector:
        est += ["--detector", args.detector]
    if args.second_model:
        est += ["--second-model", args.second_model]
    out.append(("hkf-estimator", est))
    return out


def child_setup():
    """In each child: its own process group (Ctrl-C reaches the launcher only, which stops
    the programs in order), and SIGTERM should the launcher die without stopping it."""
    os.setpgid(0, 0)
    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG


class Monitor:
    """Listens to HEAD_POSE_RAW and HEAD_POSE; one status line a second."""

    def __init__(self, url, clock_is_real):
        from hkf import head_pose_measurement_t, head_pose_t
        self.clock_is_real = clock_is_real  # a camera, or a file at its frame rate: stamps on the wall clock
        self.raw_t, self.pose_t = head_pose_measurement_t, head_pose_t
        self.lc = lcm.LCM(url)
        self.lc.subscribe("HEAD_POSE_RAW", self.on_raw)
        self.lc.subscribe("HEAD_POSE", self.on_pose)
        self.raw = self.faces = self.poses = self.second = 0
        self.latency_ms = []
        self.last = None
        self.total_poses = 0
        self.last_seq = None

    def on_raw(self, channel, data):
        m = self.raw_t.decode(data)
        if self.last_seq is not None and self.last_seq - 300 < m.seq <= self.last_seq:
            self.second += 1  # a second model's measurement of a frame already counted (it may come late)
            return
        self.last_seq = m.seq
        self.raw += 1
        self.faces += bool(m.valid)

    def on_pose(self, channel, data):
        p = self.pose_t.decode(data)
        self.poses += 1
        self.total_poses += 1
        if not p.extrapolated:
            self.latency_ms.append(p.latency_us / 1000.0)
        self.last = p

    def line(self, elapsed, interval):
        text = (f"[{elapsed:6.1f} s] camera {self.raw / interval:5.1f} fps ({self.faces} with a face), "
                f"filter {self.poses / interval:5.1f} poses/s")
        if self.second:
            text += f", second model {self.second / interval:4.1f}/s"
        if self.latency_ms and self.clock_is_real:
            lat = sorted(self.latency_ms)
            text += f", capture->pose p50 {lat[len(lat) // 2]:.1f} ms max {lat[-1]:.1f} ms"
        elif self.latency_ms:  # a file read as fast as it goes: its stamps are the file's time, not the clock
            text += ", no latency (a file faster than real time: --realtime measures it)"
        if self.last is not None:
            p = self.last
            yaw = (p.yaw - p.center[1] + 180.0) % 360.0 - 180.0
            text += (f", {STATUS.get(p.status, '?')} pitch {p.pitch - p.center[0]:+6.1f} yaw {yaw:+6.1f} "
                     f"roll {p.roll - p.center[2]:+6.1f} deg")
            if p.z > 0:  # a position: x, y, z from the centre position
                text += (f", x {p.x - p.position_center[0]:+5.1f} y {p.y - p.position_center[1]:+5.1f} "
                         f"z {p.z - p.position_center[2]:+5.1f} cm")
            text += " from centre"
        self.raw = self.faces = self.poses = self.second = 0
        self.latency_ms = []
        return text


def stop(children, logs):
    """SIGINT to each program, the estimator first; SIGKILL after a grace period. Returns each
    program's exit code, and the programs whose log holds nothing (their output was lost)."""
    codes, lost = {}, []
    for name, proc in reversed(children):
        if proc.poll() is None:
            proc.send_signal(signal.SIGINT)
            try:
                proc.wait(timeout=5)
            except subprocess.TimeoutExpired:
                print(f"hkf-track: {name} did not stop within 5 s; killed", file=sys.stderr)
                proc.kill()
                proc.wait()
        codes[name] = proc.returncode
    for name, _ in children:  # each program's summary: its last count line, and its last line
        with open(logs[name]) as f:
            lines = [l.rstrip("\n") for l in f if l.strip()]
        counts = [l for l in lines if re.match(re.escape(name) + r": \d+ ", l)]
        for line in dict.fromkeys(counts[-1:] + lines[-1:]):
            print(line)
        if not lines:  # every program says what it does when it starts: its output was lost
            print(f"hkf-track: {name}'s log {logs[name]} is empty: its output was lost (a full disk?)",
                  file=sys.stderr)
            lost.append(name)
    return codes, lost


def main():
    args = parse_args()
    sys.path.insert(0, layout(args)[2])
    for _, argv in commands(args):
        if not os.access(argv[0], os.X_OK):
            print(f"hkf-track: {argv[0]} is missing: build first (./run build)", file=sys.stderr)
            return 2
    os.makedirs(args.logs, exist_ok=True)
    stop_requested = []
    signal.signal(signal.SIGINT, lambda *_: stop_requested.append("SIGINT"))
    signal.signal(signal.SIGTERM, lambda *_: stop_requested.append("SIGTERM"))
    signal.signal(signal.SIGHUP, lambda *_: stop_requested.append("SIGHUP"))  # the terminal closed
    monitor = Monitor(args.lcm_url, clock_is_real=args.camera is not None or args.realtime)
    children, logs = [], {}
    for name, argv in commands(args):
        logs[name] = os.path.join(args.logs, name + ".log")
        with open(logs[name], "w") as log:
            proc = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT,
                                    preexec_fn=child_setup)
        children.append((name, proc))
        print(f"hkf-track: started {name} (pid {proc.pid}): {shlex.join(argv)}", flush=True)
        time.sleep(0.3)  # the subscribers are listening before the estimator publishes
    print(f"hkf-track: logs in {args.logs}; Ctrl-C stops", flush=True)

    started = time.monotonic()
    next_line = started + 1.0
    ended = None
    fd = monitor.lc.fileno()
    while not stop_requested:
        now = time.monotonic()
        if args.seconds and now - started >= args.seconds:
            break
        try:
            ready, _, _ = select.select([fd], [], [], max(0.0, min(0.1, next_line - now)))
        except InterruptedError:
            continue
        if ready:
            monitor.lc.handle()
        if time.monotonic() >= next_line:
            print(monitor.line(time.monotonic() - started, 1.0), flush=True)
            next_line += 1.0
        ended = next(((n, p) for n, p in children if p.poll() is not None), None)
        if ended:
            break

    status = 0
    if ended is not None:
        name, proc = ended
        if name == "hkf-estimator" and proc.returncode == 0:
            print("hkf-track: the source ended", flush=True)
        else:
            print(f"hkf-track: {name} stopped with status {proc.returncode}; see {logs[name]}", file=sys.stderr)
            status = 1
    elif stop_requested:
        print(f"hkf-track: {stop_requested[0]}: stopping", flush=True)
    codes, lost = stop(children, logs)
    bad = [n for n, c in codes.items() if c not in (0, -signal.SIGINT) and (ended is None or n != ended[0])]
    for name in bad:
        print(f"hkf-track: {name} exited with status {codes[name]}; see {logs[name]}", file=sys.stderr)
    print(f"hkf-track: {monitor.total_poses} filtered poses in {time.monotonic() - started:.1f} s", flush=True)
    return 1 if bad or lost else status


if __name__ == "__main__":
    sys.exit(main())
