#!/usr/bin/env python3
"""Cheap ways to read WHENet better, tried on AFLW2000's development split through the default pipeline
(`hkf-estimator --dataset`: the mesh, WHENet fused in from 10 deg and alone from 25 deg):
- test-time flip averaging: the mirrored crop read too, its yaw and roll negated, the two averaged;
- more context in the crop: a wider margin everywhere, or only where the first reading is a profile;
- a crop moved toward the back of the head by the sign of the first reading's yaw.

Each variant is a model description (whenet.model with the keys of model_spec.hpp's tried variants) in a
scratch folder given to --spec-dir; its predictions are made once (delete OUT to make them again: ~100 s each). Per labelled |yaw| bin, the mean of the three axes' MAE on the even images
(tuning) and on the odd ones (held out), and WHENet's cost per image; a variant is kept only where both halves
gain at 30-60 or 60-99 and neither loses elsewhere.

usage: crop_variants.py --build build --dataset ../shared/data/aflw2000 --out out/eval/crops [--limit N]
"""
import argparse
import csv
import os
import re
import subprocess
import sys

import numpy as np

VARIANTS = [  # name, the keys added to whenet.model
    ("default", ""),
    ("flip", "flip_average = yes"),
    ("margin 0.1", "crop_margin = 0.1"),
    ("margin 0.15", "crop_margin = 0.15"),
    ("margin 0.3", "crop_margin = 0.3"),
    ("margin 0.4", "crop_margin = 0.4"),
    ("profile 30: margin 0.35", "profile_from = 30\nprofile_margin = 0.35"),
    ("profile 30: margin 0.5", "profile_from = 30\nprofile_margin = 0.5"),
    ("profile 30: back +0.1", "profile_from = 30\nprofile_shift = 0.1"),
    ("profile 30: back -0.05", "profile_from = 30\nprofile_shift = -0.05"),
    ("profile 30: back -0.1", "profile_from = 30\nprofile_shift = -0.1"),
    ("profile 30: back -0.2", "profile_from = 30\nprofile_shift = -0.2"),
    ("flip + profile 30: margin 0.35", "flip_average = yes\nprofile_from = 30\nprofile_margin = 0.35"),
]
BINS = [(0, 30), (30, 60), (60, 99)]


def run_variant(args, name, keys, spec_root):
    """The default pipeline's predictions with this variant's whenet.model; (csv path, ms per image)."""
    slug = re.sub(r"[^a-z0-9]+", "_", name.replace("+", "plus").replace("-", "minus")).strip("_")
    spec_dir = os.path.join(spec_root, slug)
    os.makedirs(spec_dir, exist_ok=True)
    for model in ("mesh_pnp", "whenet"):
        with open(os.path.join("estimator", "models", model + ".model")) as f:
            text = f.read()
        with open(os.path.join(spec_dir, model + ".model"), "w") as f:
            f.write(text + ("\n" + keys + "\n" if model == "whenet" and keys else ""))
    predictions, summary = os.path.join(args.out, slug + ".csv"), os.path.join(args.out, slug + ".txt")
    if not (os.path.getsize(predictions) > 0 if os.path.exists(predictions) else False):  # made once
        command = [os.path.join(args.build, "estimator", "hkf-estimator"), "--dataset", args.dataset, "--spec-dir",
                   spec_dir, "--predictions", predictions + ".part"] + (["--limit", str(args.limit)] if args.limit else [])
        done = subprocess.run(command, capture_output=True, text=True)
        if done.returncode != 0:
            sys.exit(f"crop_variants: {name}: hkf-estimator failed:\n{done.stderr[-2000:]}")
        with open(summary, "w") as f:
            f.write(done.stdout + done.stderr)
        os.replace(predictions + ".part", predictions)
    with open(summary) as f:
        cost = re.search(r"([0-9.]+) ms per image", f.read())
    return predictions, float(cost.group(1)) if cost else float("nan")


def labels(dataset):
    rows = {}
    with open(os.path.join(dataset, "labels.csv")) as f:
        for i, row in enumerate(csv.DictReader(f)):
            truth = np.array([float(row["pitch_deg"]), float(row["yaw_deg"]), -float(row["roll_deg"])])
            if np.max(np.abs(truth)) <= 99.0:
                rows[row["image"]] = (i, truth)
    return rows


def bin_errors(truth, predictions_path):
    """Per half (even, odd) and bin: the mean of the three axes' MAE, and the count of yaw errors > 20 deg."""
    with open(predictions_path) as f:
        got = {r["image"]: np.array([float(r["pitch_deg"]), float(r["yaw_deg"]), float(r["roll_deg"])])
               for r in csv.DictReader(f)}
    table = {}
    for half in (0, 1):
        for lo, hi in BINS:
            errs = [np.abs(got[image] - t) for image, (i, t) in truth.items()
                    if i % 2 == half and image in got and lo <= abs(t[1]) < (hi if hi < 99 else 1e9)]
            errs = np.array(errs) if errs else np.zeros((0, 3))
            table[half, lo] = (errs.mean() if len(errs) else float("nan"), int(np.sum(errs[:, 1] > 20.0)), len(errs))
    return table


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default="build")
    parser.add_argument("--dataset", default="../shared/data/aflw2000")
    parser.add_argument("--out", default="out/eval/crops")
    parser.add_argument("--limit", type=int, default=0)
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    truth = labels(args.dataset)
    header = ("| variant | ms / image | " + " | ".join(f"{lo}-{hi} even / odd" for lo, hi in BINS) +
              " | yaw > 20 deg even / odd |")
    lines = [header, "|" + " --- |" * (3 + len(BINS))]
    for n, (name, keys) in enumerate(VARIANTS, 1):
        print(f"crop_variants: {n}/{len(VARIANTS)} {name}", flush=True)
        path, cost = run_variant(args, name, keys, os.path.join(args.out, "descriptions"))
        t = bin_errors(truth, path)
        cells = [f"{t[0, lo][0]:.2f} / {t[1, lo][0]:.2f}" for lo, _ in BINS]
        gross = [sum(t[h, lo][1] for lo, _ in BINS) for h in (0, 1)]
        lines.append(f"| {name} | {cost:.1f} | " + " | ".join(cells) + f" | {gross[0]} / {gross[1]} |")
        print(lines[-1], flush=True)
    counts = [f"{lo}-{hi}: {t[0, lo][2]} / {t[1, lo][2]}" for lo, hi in BINS]  # the last variant's table: every one has them
    report = ("Mean of the three axes' MAE (deg) per labelled |yaw| bin, the default pipeline, AFLW2000 development "
              "split, even images / odd images (images " + ", ".join(counts) + "):\n\n" + "\n".join(lines) + "\n")
    with open(os.path.join(args.out, "crop_variants.md"), "w") as f:
        f.write(report)
    print("\n" + report)


if __name__ == "__main__":
    main()
