#!/usr/bin/env python3
"""Shows that a change keeps the programs' outputs bit for bit: the shared clips
through two revisions' programs, compared.

For each revision (BEFORE as a git worktree; AFTER likewise, or the working
tree when not given) the programs are built in WORK/<rev>/build. Then, per
shared clip:
  - hkf-estimator of each revision on the clip (as fast as it goes): the first
    model's measurements must be the same message for message, its two times
    aside (utime: a file read as fast as it goes is stamped on the wall clock at
    capture; inference_us). The second model runs on its own thread and takes the
    newest frame it is asked for, so which frames it measures depends on
    timing: its measurements are counted, not compared.
  - hkf-filter --offline of each revision on one raw log (BEFORE's estimator's,
    so both filters read the same bytes): the output logs and the CSVs must be
    identical byte for byte.
Prints a table and exits 0 when everything is identical, 1 when not, 2 on bad
input.

usage: .venv/bin/python dev/refactor/same_outputs.py BEFORE [AFTER] [--clips d0,d3,...] [--work DIR]
"""
import argparse
import csv
import filecmp
import os
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
VIDEOS = os.path.join(ROOT, "..", "shared", "data", "videos")
CLIPS = ["d0", "d3", "d9", "d10", "d11", "d12", "d14", "d18", "s18", "s20"]
PROGRAMS = ["hkf-estimator", "hkf-filter"]


def fail(message, code=2):
    print(f"same_outputs: {message}", file=sys.stderr)
    sys.exit(code)


def run(command, **kwargs):
    result = subprocess.run(command, capture_output=True, text=True, **kwargs)
    if result.returncode != 0:
        fail(f"{' '.join(command)} exited {result.returncode}: {(result.stdout + result.stderr)[-800:]}")
    return result


def source_of(revision, work):
    """The source tree of a revision: a detached worktree (made once), or the working tree for None."""
    if revision is None:
        return ROOT
    commit = run(["git", "rev-parse", "--verify", revision + "^{commit}"], cwd=ROOT).stdout.strip()
    tree = os.path.join(work, commit[:12], "src")
    if not os.path.exists(tree):
        run(["git", "worktree", "add", "--detach", tree, commit], cwd=ROOT)
        for link in (".models", ".venv"):  # the set-up's, shared
            os.symlink(os.path.join(ROOT, link), os.path.join(tree, link))
        if not os.path.lexists(os.path.join(os.path.dirname(tree), "shared")):  # ../shared, as beside a checkout
            os.symlink(os.path.abspath(os.path.join(ROOT, "..", "shared")), os.path.join(os.path.dirname(tree), "shared"))
    return tree


def build(source, build_dir):
    """The programs of one tree; their folder."""
    run(["cmake", "-S", source, "-B", build_dir, "-G", "Ninja", "-DHKF_BUILD_TESTS=OFF", "-DHKF_BUILD_BENCHMARKS=OFF"])
    run(["cmake", "--build", build_dir, "-j", str(os.cpu_count() or 2), "--target", *PROGRAMS])
    return build_dir


def measurements(log, types):
    """The first model's measurements of a raw log (utime and inference_us zeroed), and the second model's count."""
    sys.path.insert(0, types)
    import lcm
    from hkf import head_pose_measurement_t
    first, second, model = [], 0, None
    for event in lcm.EventLog(log, "r"):
        if event.channel != "HEAD_POSE_RAW":
            continue
        m = head_pose_measurement_t.decode(event.data)
        model = model or m.model
        if m.model != model:
            second += 1
            continue
        m.utime = m.inference_us = 0
        first.append(m.encode())
    return first, second


def shipped_config(source):
    """A tree's hkf-filter.conf: filter_node/ (from the node's own room on), or tools/filter_node/ before."""
    path = os.path.join(source, "filter_node", "hkf-filter.conf")
    return path if os.path.exists(path) else os.path.join(source, "tools", "filter_node", "hkf-filter.conf")


def largest_differences(csv_a, csv_b):
    """The largest |pitch|, |yaw| or |roll| difference (deg) and the largest |x|, |y| or |z| difference (cm)
    between two pose CSVs of the same frames, or None when their rows are not the same frames."""
    with open(csv_a) as a, open(csv_b) as b:
        rows_a, rows_b = list(csv.DictReader(a)), list(csv.DictReader(b))
    if [r["utime"] for r in rows_a] != [r["utime"] for r in rows_b]:
        return None
    angle = position = 0.0
    for ra, rb in zip(rows_a, rows_b):
        for axis in ("pitch", "yaw", "roll"):
            d = abs(float(ra[axis]) - float(rb[axis]))
            angle = max(angle, min(d, 360.0 - d) if axis == "yaw" else d)
        for axis in ("x", "y", "z"):
            position = max(position, abs(float(ra[axis]) - float(rb[axis])))
    return angle, position


def clip_row(clip, builds, work, types):
    """(clip, first-model measurements, same?, second-model counts, poses, same?, largest angle difference) for
    one clip. Each revision's hkf-filter reads its own tree's hkf-filter.conf."""
    video = os.path.join(VIDEOS, clip + ".mp4")
    raw = []
    for name, build_dir, _ in builds:
        log = os.path.join(work, f"{clip}.{name}.raw.lcmlog")
        run([os.path.join(build_dir, "estimator", "hkf-estimator"), "--source", video, "--lcm-url", f"file://{log}?mode=w"])
        raw.append((log, *measurements(log, types)))
    outputs = []
    for name, build_dir, source in builds:  # both filters on BEFORE's raw log
        out, poses = os.path.join(work, f"{clip}.{name}.poses.lcmlog"), os.path.join(work, f"{clip}.{name}.poses.csv")
        run([os.path.join(build_dir, "tools", "hkf-filter"), "--config", shipped_config(source), "--offline", raw[0][0],
             out, "--csv", poses])
        outputs.append((out, poses))
    same_raw = raw[0][1] == raw[1][1]
    same_poses = all(filecmp.cmp(a, b, shallow=False) for a, b in zip(outputs[0], outputs[1]))
    lines = sum(1 for _ in open(outputs[0][1])) - 1
    return (clip, len(raw[0][1]), same_raw, (raw[0][2], raw[1][2]), lines, same_poses,
            largest_differences(outputs[0][1], outputs[1][1]))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], epilog=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("before")
    parser.add_argument("after", nargs="?", help="default: the working tree")
    parser.add_argument("--clips", default=",".join(CLIPS))
    parser.add_argument("--work", default=os.path.join(ROOT, "out", "same_outputs"))
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    builds = []
    for label, revision in (("before", args.before), ("after", args.after)):
        source = source_of(revision, args.work)
        print(f"same_outputs: building {label} ({revision or 'the working tree'})", flush=True)
        folder = os.path.dirname(source) if revision is not None else os.path.join(args.work, "working-tree")
        builds.append((label, build(source, os.path.join(folder, "build")), source))
    types = os.path.join(builds[0][1], "lcmtypes", "python")
    print("| clip | first model's measurements | identical | second model's (before / after) | poses | identical (log, CSV) "
          "| largest angle difference | largest position difference |")
    print("| --- | ---: | --- | ---: | ---: | --- | ---: | ---: |")
    differs = 0
    for clip in args.clips.split(","):
        if not os.path.exists(os.path.join(VIDEOS, clip + ".mp4")):
            fail(f"no {clip}.mp4 in {VIDEOS}")
        name, count, same_raw, seconds, poses, same_poses, largest = clip_row(clip, builds, args.work, types)
        differs += (not same_raw) + (not same_poses)
        print(f"| {name} | {count} | {'yes' if same_raw else 'NO'} | {seconds[0]} / {seconds[1]} | {poses} | "
              f"{'yes' if same_poses else 'NO'} | "
              f"{'other frames | ' if largest is None else f'{largest[0]:.2g} deg | {largest[1]:.2g} cm'} |",
              flush=True)
    print("same_outputs: " + ("every output identical" if not differs else f"{differs} outputs differ"))
    return 1 if differs else 0


if __name__ == "__main__":
    sys.exit(main())
