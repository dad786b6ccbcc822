#!/usr/bin/env python3
"""How each head-pose model errs by head turn, and what continuous fusion weights and a gross-error check
would make of it, on AFLW2000's development split (the only part of the benchmark the project has).

Input: `hkf-estimator --dataset` predictions of each model alone on the same images (the live path) and the
labels. Per model and labelled |yaw| range (15 deg wide), per axis: the images it measured, the bias (the mean
signed error; yaw's signed toward the turn, so a negative bias under-reads the turn), the spread (the standard
deviation of the error) and the share of gross errors (more than 20 deg off).

Then, per AFLW2000 |yaw| bin (0-30, 30-60, 60-99 deg), the mean of the three axes' MAE of four ways to join the
two models on a single image, tuned on the even images and reported on the odd ones (and the reverse):
- the pipeline: the mesh; WHENet fused in (each R by its Eq. 8 curve) where the mesh's |yaw| >= 10 deg, alone from
  25 deg or where the mesh has no pose (fusion_on_aflw.py's pipeline row; hkf-estimator --dataset's default);
- continuous weights: where the pipeline runs WHENet, each model weighted by the inverse of its mean squared error
  at the angle it reads (fitted on the tuning half per axis in 10 deg bins of the mesh's |yaw| reading, WHENet's
  where the mesh has none, linear between bin centres), so the weights follow the angle with no switch;
- either, with a gross-error check: where the two models' yaw readings differ by more than 20 deg, the one the
  tuning half found right more often in such disagreements at that reading is taken alone;
- the pipeline with the mesh's yaw less its bias at its reading (the tuning half's mean signed error in 10 deg bins
  of the mesh's |yaw|, linear between bin centres): the mesh under-reads a turn more the further it is.

usage: model_ranges.py --labels L.csv --mesh MESH.csv --whenet WHENET.csv [--filter build/tools/hkf-filter]
"""
import argparse
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fusion_on_aflw  # noqa: E402

RANGES = [(0, 15), (15, 30), (30, 45), (45, 60), (60, 75), (75, 99)]
BINS = fusion_on_aflw.BINS
AXES = ("pitch", "yaw", "roll")
GROSS_DEG = 20.0
SECOND_FROM_YAW, SECOND_ALONE_FROM_YAW = 10.0, 25.0  # the live pipeline's rule (hkf-estimator, hkf-filter)
WEIGHT_BIN_DEG = 10.0


def load(labels_path, mesh_path, whenet_path):
    """Rows of (index, truth (3), mesh (3) or None, whenet (3) or None) within +-99 deg; roll in hkf's sense."""
    mesh, whenet = fusion_on_aflw.predictions(mesh_path), fusion_on_aflw.predictions(whenet_path)
    rows = []
    with open(labels_path) as f:
        for i, row in enumerate(csv.DictReader(f)):
            truth = np.array([float(row["pitch_deg"]), float(row["yaw_deg"]), -float(row["roll_deg"])])
            if np.max(np.abs(truth)) > 99.0:
                continue
            m, w = mesh.get(row["image"]), whenet.get(row["image"])
            rows.append((i, truth, None if m is None else np.array(m), None if w is None else np.array(w)))
    return rows


def range_table(rows, model):
    """Markdown rows: per labelled |yaw| range, per axis, n, bias, spread, gross share of one model."""
    lines = []
    for lo, hi in RANGES:
        inside = [(t, g) for _, t, m, w in rows for g in [m if model == "mesh_pnp" else w]
                  if lo <= abs(t[1]) < hi or (hi == 99 and abs(t[1]) >= lo)]
        measured = [(t, g) for t, g in inside if g is not None]
        cells = []
        for a in range(3):
            if not measured:
                cells.append("-")
                continue
            err = np.array([(g[a] - t[a]) * (np.sign(t[1]) or 1.0 if a == 1 else 1.0) for t, g in measured])
            cells.append(f"{err.mean():+.1f} / {err.std():.1f} / {100 * np.mean(np.abs(err) > GROSS_DEG):.0f} %")
        lines.append(f"| {model} | {lo}-{hi} | {len(measured)} of {len(inside)} | " + " | ".join(cells) + " |")
    return lines


def reading(m, w):
    """The angle a frame's weights are looked up at: the mesh's |yaw| reading, WHENet's where the mesh has none."""
    return abs(m[1]) if m is not None else abs(w[1])


def fit_weights(rows):
    """Per model, per axis: the mean squared error in WEIGHT_BIN_DEG bins of the reading, where both measured."""
    edges = np.arange(0.0, 100.0 + WEIGHT_BIN_DEG, WEIGHT_BIN_DEG)
    both = [(t, m, w) for _, t, m, w in rows if m is not None and w is not None and reading(m, w) >= SECOND_FROM_YAW]
    fitted = {}
    for name, pick in (("mesh_pnp", lambda m, w: m), ("whenet", lambda m, w: w)):
        table = np.full((len(edges) - 1, 3), np.nan)
        for k in range(len(edges) - 1):
            inside = [(t, pick(m, w)) for t, m, w in both if edges[k] <= reading(m, w) < edges[k + 1]]
            if len(inside) >= 5:
                table[k] = np.mean([(g - t) ** 2 for t, g in inside], axis=0)
        fitted[name] = table
    centres = (edges[:-1] + edges[1:]) / 2.0
    return centres, fitted


def mse_at(centres, table, x, a):
    ok = np.isfinite(table[:, a])
    return float(np.interp(x, centres[ok], table[ok, a]))


def fit_gross_rule(rows):
    """Per 30 deg bin of the reading: 'whenet' or 'mesh_pnp', the one nearer the label more often where the two
    models' yaw readings differ by more than GROSS_DEG."""
    rule = {}
    for lo in (0, 30, 60):
        votes = [abs(w[1] - t[1]) < abs(m[1] - t[1]) for _, t, m, w in rows
                 if m is not None and w is not None and abs(m[1] - w[1]) > GROSS_DEG and lo <= reading(m, w) < lo + 30]
        rule[lo] = "whenet" if not votes or np.mean(votes) >= 0.5 else "mesh_pnp"
    return rule


def fit_mesh_bias(rows):
    """The mesh's yaw bias toward the turn per WEIGHT_BIN_DEG bin of its own |yaw| reading (NaN: too few)."""
    edges = np.arange(0.0, 100.0 + WEIGHT_BIN_DEG, WEIGHT_BIN_DEG)
    table = np.full(len(edges) - 1, np.nan)
    for k in range(len(edges) - 1):
        errs = [(m[1] - t[1]) * (np.sign(m[1]) or 1.0) for _, t, m, _ in rows
                if m is not None and edges[k] <= abs(m[1]) < edges[k + 1]]
        if len(errs) >= 5:
            table[k] = np.mean(errs)
    return (edges[:-1] + edges[1:]) / 2.0, table


def debiased(way, bias):
    """way, given the mesh's yaw less its bias at its reading (the tuning half's)."""
    centres, table = bias
    ok = np.isfinite(table)

    def corrected(m, w):
        if m is None:
            return way(m, w)
        m = m.copy()
        m[1] -= (np.sign(m[1]) or 1.0) * float(np.interp(abs(m[1]), centres[ok], table[ok]))
        return way(m, w)
    return corrected


def pipeline_way(curves):
    c_mesh, c_whenet = curves

    def way(m, w):
        if m is None:
            return w
        if w is None or abs(m[1]) < SECOND_FROM_YAW:
            return m
        if abs(m[1]) >= SECOND_ALONE_FROM_YAW:
            return w
        wm = np.array([1.0 / fusion_on_aflw.noise(c_mesh[a], m[a]) for a in range(3)])
        ww = np.array([1.0 / fusion_on_aflw.noise(c_whenet[a], w[a]) for a in range(3)])
        return (wm * m + ww * w) / (wm + ww)
    return way


def continuous_way(fit):
    centres, fitted = fit

    def way(m, w):
        if m is None or w is None or abs(m[1]) < SECOND_FROM_YAW:
            return m if m is not None else w
        x = reading(m, w)
        wm = np.array([1.0 / max(mse_at(centres, fitted["mesh_pnp"], x, a), 1e-3) for a in range(3)])
        ww = np.array([1.0 / max(mse_at(centres, fitted["whenet"], x, a), 1e-3) for a in range(3)])
        return (wm * m + ww * w) / (wm + ww)
    return way


def with_gross_check(way, rule):
    def checked(m, w):
        if m is not None and w is not None and abs(m[1] - w[1]) > GROSS_DEG:
            return w if rule[min(int(reading(m, w) // 30) * 30, 60)] == "whenet" else m
        return way(m, w)
    return checked


def bin_mae(rows, way):
    """Per BINS bin and over all: (mean of the three axes' MAE, yaw MAE) of the images a way measured."""
    out = []
    for lo, hi in BINS + [(0.0, 100.0)]:
        errs = [np.abs(g - t) for _, t, m, w in rows for g in [way(m, w)]
                if g is not None and (lo <= abs(t[1]) < hi or (hi == 99.0 and abs(t[1]) >= lo))]
        out.append((float(np.mean(errs)), float(np.mean([e[1] for e in errs]))) if errs else (np.nan, np.nan))
    return out


def fusion_table(rows, curves):
    """Markdown rows: each way, tuned on one half, reported on the other (even -> odd, odd -> even)."""
    halves = {"even": [r for r in rows if r[0] % 2 == 0], "odd": [r for r in rows if r[0] % 2 == 1]}
    lines = []
    for tune, report in (("even", "odd"), ("odd", "even")):
        fit, rule = fit_weights(halves[tune]), fit_gross_rule(halves[tune])
        ways = [("the pipeline (switches at 10 and 25 deg)", pipeline_way(curves)),
                ("continuous weights", continuous_way(fit)),
                ("the pipeline + the gross-error check", with_gross_check(pipeline_way(curves), rule)),
                ("continuous weights + the gross-error check", with_gross_check(continuous_way(fit), rule)),
                ("the pipeline, the mesh's yaw less its bias", debiased(pipeline_way(curves), fit_mesh_bias(halves[tune])))]
        for name, way in ways:
            cells = [f"{mean:.2f} (yaw {yaw:.2f})" for mean, yaw in bin_mae(halves[report], way)]
            lines.append(f"| {name} | {tune} | {report} | " + " | ".join(cells) + " |")
        lines.append(f"| (the gross-error rule learnt on {tune}: " +
                     ", ".join(f"{lo}-{lo + 30} deg: {rule[lo]}" for lo in (0, 30, 60)) + ") | | | | | | |")
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--labels", required=True)
    parser.add_argument("--mesh", required=True, help="mesh_pnp predictions (hkf-estimator --dataset)")
    parser.add_argument("--whenet", required=True, help="whenet predictions")
    parser.add_argument("--filter", default=os.path.join(fusion_on_aflw.ROOT, "build", "tools", "hkf-filter"))
    args = parser.parse_args()
    rows = load(args.labels, args.mesh, args.whenet)
    curves = (fusion_on_aflw.curves(args.filter, "mesh_pnp"), fusion_on_aflw.curves(args.filter, "whenet"))
    lines = ["## How each model errs by head turn (AFLW2000 dev split)", "",
             "Per cell: bias / spread / gross errors (deg; yaw's bias signed toward the turn; gross: over 20 deg off).",
             "", "| model | labelled \\|yaw\\| (deg) | measured | pitch | yaw | roll |", "| --- | --- | ---: | --- | --- | --- |"]
    lines += range_table(rows, "mesh_pnp") + range_table(rows, "whenet")
    lines += ["", "## Joining the two models: tuned on one half, reported on the other", "",
              "Mean of the three axes' MAE (yaw's MAE), deg, of the images measured, by labelled |yaw|.", "",
              "| way | tuned on | reported on | " + " | ".join(f"{lo:g}-{hi:g} deg" for lo, hi in BINS) + " | all |",
              "| --- | --- | --- |" + " ---: |" * (len(BINS) + 1)]
    lines += fusion_table(rows, curves)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
