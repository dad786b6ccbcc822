import sys, os, itertools, time, pickle
import numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import proto, truth_eval, evaluate

def rows_for(clip, name, labels, outs):
    rows = []
    for j, lab in enumerate(labels):
        roll = outs[:, j]
        rows.append({"clip": clip.name, "filter": name, "setting": lab, **truth_eval.clip_metrics(clip, roll)})
    return rows

def run(clips, gpb_grid, euro_grid, extra=None, fn=None):
    rows = []
    for c in clips:
        z = c.z[:, 2]
        R = proto.noise_level(c.t, c.valid, z) * proto.e_curve(z) / proto.e_curve(proto.MU)
        qs, qm, a, b = (np.array(v, float) for v in zip(*gpb_grid))
        out = (fn or proto.gpb1)(c.t, c.valid, z, R, qs, qm, a, b)
        rows += rows_for(c, "gpb1", [f"qs {g[0]:g} qm {g[1]:g} a {g[2]:g} b {g[3]:g}" for g in gpb_grid], out)
        mc, be = (np.array(v, float) for v in zip(*euro_grid))
        out = proto.one_euro(c.t, c.valid, z, mc, be)
        rows += rows_for(c, "1 euro", [f"mc {g[0]:g} beta {g[1]:g}" for g in euro_grid], out)
        raw = np.where(c.valid, z, np.nan)[:, None]
        rows += rows_for(c, "raw", ["-"], raw)
        if extra:
            for name, fn in extra.items():
                rows += rows_for(c, name, ["-"], fn(c)[:, None])
    return rows

def frontier(pooled, name):
    pts = sorted([(p["jitter"], p["rmse_moving"], p) for p in pooled if p["filter"] == name], key=lambda x: x[0])
    front, best = [], 1e9
    for j, r, p in pts:
        if r < best:
            best = r; front.append(p)
    return front

def best_at(pooled, name, jitter):
    c = [p for p in pooled if p["filter"] == name and p["jitter"] <= jitter * 1.0001]
    return min(c, key=lambda p: p["rmse_moving"]) if c else None
