#!/usr/bin/env python3
"""What fusing the two estimators would give on AFLW2000, per
labelled |yaw| bin: faces found and mean MAE of pitch, yaw and roll, for each
estimator alone, for choosing one by WHENet's yaw, for the measurement
update hkf_update_pair makes of a single frame (inverse-variance weights,
each R from its model's Eq. 8 curves as hkf-filter has them built in), and
for the pipeline hkf-estimator --second-model whenet and hkf-filter run
(WHENet only where the mesh's yaw is beyond --second-from-yaw, fused there,
taken alone beyond --second-alone-from-yaw or where the mesh gives no pose;
a single image has no history, so the node's offset between the two models
is not applied).

Input: `hkf-estimator --dataset` predictions of both models on the same
images (the live path by default) and the dataset's labels.

usage: fusion_on_aflw.py --labels L.csv --mesh MESH.csv --whenet WHENET.csv [--limit N]
                         [--filter build/tools/hkf-filter] [--select-yaw DEG] [--second-from-yaw DEG]
                         [--second-alone-from-yaw DEG] [--part all|even|odd]
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
BINS = [(0.0, 30.0), (30.0, 60.0), (60.0, 99.0)]
R_MIN, R_MAX = 1e-3, 1e4  # hkf-filter's default clamp of R, deg^2


def fail(message):
    print(f"fusion_on_aflw: {message}", file=sys.stderr)
    sys.exit(1)


def curves(filter_path, model):
    """(tau, lambda, mu, sigma) per axis of a model built into hkf-filter (its --print-config)."""
    try:
        text = subprocess.run([filter_path, "--print-config"], capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError) as e:
        fail(f"cannot run {filter_path} --print-config: {e}")
    section = re.search(rf"^\[model {model}\]\n(.*?)(?:\n\n|\Z)", text, re.S | re.M)
    if section is None:
        fail(f"hkf-filter has no [model {model}]")
    found = []
    for axis in ("pitch", "yaw", "roll"):
        line = re.search(rf"^noise\.{axis}\s*=\s*(\S+) (\S+) (\S+) (\S+)", section.group(1), re.M)
        found.append(tuple(float(v) for v in line.groups()))
    return found


def noise(curve, x):
    """Paper Eq. 8 (amplitude form), clamped as hkf-filter clamps it."""
    tau, lam, mu, sigma = curve
    return min(max(tau - lam * math.exp(-(x - mu) ** 2 / (2.0 * sigma * sigma)), R_MIN), R_MAX)


def predictions(path):
    try:
        with open(path) as f:
            return {r["image"]: [float(r["pitch_deg"]), float(r["yaw_deg"]), float(r["roll_deg"])]
                    for r in csv.DictReader(f)}
    except (OSError, KeyError, ValueError) as e:
        fail(f"{path}: not an hkf-estimator --dataset predictions CSV ({e})")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    parser.add_argument("--labels", required=True)
    parser.add_argument("--mesh", required=True, help="mesh_pnp predictions")
    parser.add_argument("--whenet", required=True, help="whenet predictions")
    parser.add_argument("--filter", default=os.path.join(ROOT, "build", "tools", "hkf-filter"))
    parser.add_argument("--limit", type=int, default=0,
                        help="only the first N labelled images, as hkf-estimator --limit N (0: all)")
    parser.add_argument("--select-yaw", type=float, default=30.0,
                        help="the choice rule takes WHENet where its |yaw| is at least this, deg (default 30)")
    parser.add_argument("--second-from-yaw", type=float, default=10.0,
                        help="the pipeline row: WHENet runs where the mesh's |yaw| is at least this, deg, as "
                             "hkf-estimator --second-from-yaw (default 10)")
    parser.add_argument("--second-alone-from-yaw", type=float, default=25.0,
                        help="the pipeline row: WHENet alone where the mesh's |yaw| is at least this, deg, as "
                             "hkf-filter's pair_second_alone_from_yaw (default 25)")
    parser.add_argument("--part", choices=["all", "even", "odd"], default="all",
                        help="only the even or odd labelled images (tuning and held-out halves)")
    args = parser.parse_args()
    mesh, whenet = predictions(args.mesh), predictions(args.whenet)
    c_mesh, c_whenet = curves(args.filter, "mesh_pnp"), curves(args.filter, "whenet")

    def fused(m, w):  # the posterior of one hkf_update_pair measurement step, per axis
        return [(m[a] / noise(c_mesh[a], m[a]) + w[a] / noise(c_whenet[a], w[a])) /
                (1.0 / noise(c_mesh[a], m[a]) + 1.0 / noise(c_whenet[a], w[a])) for a in range(3)]

    def pipeline(m, w):  # what hkf-estimator --second-model whenet and hkf-filter make of one frame
        if m is None:
            return w
        if w is None or abs(m[1]) < args.second_from_yaw:
            return m
        return w if abs(m[1]) >= args.second_alone_from_yaw else fused(m, w)

    ways = {
        "mesh_pnp": lambda m, w: m,
        "whenet": lambda m, w: w,
        f"WHENet where it measures yaw beyond ±{args.select_yaw:g}°, else mesh_pnp": lambda m, w:
            w if (w is not None and (m is None or abs(w[1]) >= args.select_yaw)) else m,
        "fused: inverse-variance, each R by Eq. 8 at its own angle": lambda m, w:
            fused(m, w) if (m is not None and w is not None) else (m if m is not None else w),
        f"the pipeline (`--second-model whenet`): mesh_pnp; WHENet fused in where the mesh's yaw is beyond "
        f"±{args.second_from_yaw:g}°, alone beyond ±{args.second_alone_from_yaw:g}° or where the mesh gives no pose":
            pipeline,
    }
    try:
        with open(args.labels) as f:
            labels = list(csv.DictReader(f))[: args.limit or None]
        if args.part != "all":
            labels = labels[args.part == "odd"::2]
    except OSError as e:
        fail(f"cannot read {args.labels}: {e}")
    print("| estimate | " + " | ".join(f"labelled yaw ±{lo:g}-{hi:g}°" for lo, hi in BINS) + " | all |")
    print("| --- |" + " --- |" * (len(BINS) + 1))
    for name, way in ways.items():
        found, errors = [[0, 0] for _ in BINS], [[] for _ in BINS]
        for row in labels:
            truth = [float(row["pitch_deg"]), float(row["yaw_deg"]), -float(row["roll_deg"])]  # roll: hkf's sense
            if max(abs(v) for v in truth) > 99.0:
                continue
            b = next(i for i, (lo, hi) in enumerate(BINS) if abs(truth[1]) < hi or i == len(BINS) - 1)
            guess = way(mesh.get(row["image"]), whenet.get(row["image"]))
            found[b][1] += 1
            if guess is not None:
                found[b][0] += 1
                errors[b].append(sum(abs(guess[a] - truth[a]) for a in range(3)) / 3.0)
        cells = [f"{100.0 * k / max(n, 1):.1f} %, {sum(e) / max(len(e), 1):.2f}°" for (k, n), e in zip(found, errors)]
        everything = [x for e in errors for x in e]
        total = sum(n for _, n in found)
        cells.append(f"{100.0 * len(everything) / max(total, 1):.1f} %, {sum(everything) / max(len(everything), 1):.2f}°")
        print(f"| {name} | " + " | ".join(cells) + " |")
    print("\n(faces found, then the mean of the pitch, yaw and roll MAE of the faces found)")


if __name__ == "__main__":
    main()
