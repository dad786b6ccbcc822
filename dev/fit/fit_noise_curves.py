#!/usr/bin/env python3
"""The paper's Table I procedure for an estimator we ship: its absolute error on
AFLW2000, binned by the labelled angle of each axis (the paper's Figs. 2-3),
fitted with Eq. 8 in amplitude form,
    e(x) = tau - lambda * exp(-(x - mu)^2 / (2 sigma^2)),
weighted by bin count. Prints the bins, the fit and its residual, draws the
binned errors with the fitted curves (PNG), and prints a [model NAME] section
for hkf-filter.conf.

Input: hkf-estimator --dataset's predictions CSV (image,pitch_deg,yaw_deg,
roll_deg; hkf convention) and the dataset's labels.csv (image,yaw_deg,pitch_deg,
roll_deg,...; roll is the negative of hkf's). The standard protocol: images
whose three labelled angles are all within +-99 deg.
usage: fit_noise_curves.py --labels L.csv --predictions P.csv --model NAME --png OUT.png"""
import argparse
import csv
import math
import sys

import numpy as np
from scipy.optimize import curve_fit

AXES = ("pitch", "yaw", "roll")
EDGES = np.arange(-90, 91, 10, dtype=float)  # 18 bins of 10 deg; +-90..99 join the outer bins
MIN_COUNT = 5                                # fewer images than this: the bin's mean is noise
# Bounds of (floor = tau - lambda, lambda, mu, sigma): the error at mu is >= 0 and
# the dip opens upward. Where the error grows quadratically over the whole range
# (as in the paper's roll rows, tau ~ 3e5) only lambda / sigma^2 is determined;
# lambda is then held at 1e4, hkf-filter's r_max (a larger R is clamped anyway),
# which keeps the numbers small (and within reach of a fixed-point build).
LOWER = (0.0, 0.0, -45.0, 1.0)
UPPER = (90.0, 1e4, 45.0, 1e5)


def eq8(x, floor, depth, mu, sigma):
    """Eq. 8 as floor + lambda (1 - exp(-u)): tau = floor + lambda, without cancelling."""
    return floor - depth * np.expm1(-((x - mu) ** 2) / (2.0 * sigma ** 2))


def number(value, decimals):
    """value rounded to `decimals` places, without trailing zeros."""
    text = f"{value:.{decimals}f}".rstrip("0").rstrip(".")
    return "0" if text in ("", "-0") else text


def read_rows(labels_path, predictions_path):
    with open(predictions_path) as f:
        predicted = {r["image"]: r for r in csv.DictReader(f)}
    truth, errors, missing = [], [], 0
    with open(labels_path) as f:
        for r in csv.DictReader(f):
            label = (float(r["pitch_deg"]), float(r["yaw_deg"]), -float(r["roll_deg"]))
            if max(abs(v) for v in label) > 99.0:
                continue
            p = predicted.get(r["image"])
            if p is None:
                missing += 1  # no face found: not part of the error statistics
                continue
            guess = (float(p["pitch_deg"]), float(p["yaw_deg"]), float(p["roll_deg"]))
            truth.append(label)
            errors.append([abs((g - t + 180.0) % 360.0 - 180.0) for g, t in zip(guess, label)])
    return np.array(truth), np.array(errors), missing


def bin_errors(angle, error):
    index = np.clip(np.digitize(angle, EDGES) - 1, 0, len(EDGES) - 2)
    bins = []
    for b in range(len(EDGES) - 1):
        chosen = error[index == b]
        if len(chosen) >= MIN_COUNT:
            bins.append((0.5 * (EDGES[b] + EDGES[b + 1]), len(chosen), float(np.mean(chosen))))
    return bins


def fit_axis(bins):
    centres = np.array([b[0] for b in bins])
    counts = np.array([b[1] for b in bins], dtype=float)
    means = np.array([b[2] for b in bins])
    start = (max(means.min(), 0.1), max(means.max() - means.min(), 0.1), 0.0, 40.0)
    params, _ = curve_fit(eq8, centres, means, p0=start, sigma=1.0 / np.sqrt(counts), bounds=(LOWER, UPPER),
                          maxfev=20000)
    fitted = eq8(centres, *params)
    residual = float(np.sqrt(np.sum(counts * (means - fitted) ** 2) / np.sum(counts)))  # count-weighted RMS
    return params, residual, float(np.max(np.abs(means - fitted)))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--labels", required=True)
    parser.add_argument("--predictions", required=True)
    parser.add_argument("--model", required=True, help="the estimator model's name, as in its messages")
    parser.add_argument("--png", help="draw the binned errors and the fitted curves here")
    args = parser.parse_args()
    try:
        truth, errors, missing = read_rows(args.labels, args.predictions)
    except (OSError, KeyError, ValueError) as e:
        sys.exit(f"fit_noise_curves: {e}")
    if len(truth) < 100:
        sys.exit(f"fit_noise_curves: only {len(truth)} images with a prediction; the fit needs more")
    print(f"fit_noise_curves: {args.model}: {len(truth)} images within +-99 deg with a prediction "
          f"({missing} without a face, left out)")
    section, curves = [f"[model {args.model}]"], []
    for a, axis in enumerate(AXES):
        bins = bin_errors(truth[:, a], errors[:, a])
        (floor, depth, mu, sigma), residual, worst = fit_axis(bins)
        tau = floor + depth
        curves.append((axis, bins, (floor, depth, mu, sigma)))
        print(f"  {axis}: " + ", ".join(f"{c:+.0f}:{m:.1f}({n})" for c, n, m in bins))
        print(f"  {axis}: tau {tau:.6g}, lambda {depth:.6g}, mu {mu:.3g}, sigma {sigma:.4g}; error at mu "
              f"{floor:.2f} deg, at -90/+90 {eq8(-90.0, floor, depth, mu, sigma):.1f}/"
              f"{eq8(90.0, floor, depth, mu, sigma):.1f} deg; residual (count-weighted RMS) {residual:.2f} deg, "
              f"worst bin {worst:.2f} deg" + (" (lambda at its bound: quadratic over this range)"
                                               if depth >= UPPER[1] * 0.999 else ""))
        # tau to 0.001 deg: tau - lambda (the error at mu) must keep its digits when tau is ~1e4
        section.append(f"noise.{axis:<14} = {number(tau, 3)} {number(depth, 3)} {number(mu, 3)} {number(sigma, 2)}")
    section.append("r_const              = " + " ".join(number(c[2][0], 3) for c in curves))
    print("\n".join(section))
    if args.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        figure, panels = plt.subplots(1, 3, figsize=(13, 4), sharey=True)
        x = np.linspace(-99, 99, 400)
        for panel, (axis, bins, params) in zip(panels, curves):
            panel.bar([b[0] for b in bins], [b[2] for b in bins], width=9, color="#9ec5e8", label="mean |error| per bin")
            for c, n, m in bins:
                panel.text(c, m, str(n), ha="center", va="bottom", fontsize=6)
            panel.plot(x, eq8(x, *params), "r-", label="Eq. 8 fit")
            panel.set_title(f"{args.model}: {axis}")
            panel.set_xlabel(f"labelled {axis} (deg)")
        panels[0].set_ylabel("mean absolute error (deg)")
        panels[0].legend(fontsize=8)
        figure.tight_layout()
        figure.savefig(args.png, dpi=100)
        print(f"fit_noise_curves: wrote {args.png}")


if __name__ == "__main__":
    main()
