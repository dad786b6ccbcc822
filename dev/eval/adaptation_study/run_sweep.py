import os, sys, time, itertools, numpy as np, pickle
OUT_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', '..', 'out', 'eval', 'adaptation_study')
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import proto, sweep, truth_eval, evaluate
clips = proto.load_clips()
tune = [c for c in clips if c.source in evaluate.TUNING_CLIPS]
held = [c for c in clips if c.source not in evaluate.TUNING_CLIPS]
gpb = list(itertools.product([0, 1e-5], [12000, 16000], [0.01, 0.02, 0.03, 0.05], [8, 16, 32]))
euro = list(itertools.product([0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1, 2], [0.1, 0.2, 0.3, 0.4, 0.5, 0.7, 1, 1.5]))
res = {}
for label, cs in (("tune", tune), ("held", held)):
    rows = sweep.run(cs, gpb, euro, fn=proto.gpb1_hold)
    res[label] = truth_eval.pool(rows)
os.makedirs(OUT_DIR, exist_ok=True)
pickle.dump(res, open(os.path.join(OUT_DIR, "sweep.pkl"), "wb"))
for share in (0.08, 0.09, 0.10, 0.11, 0.12, 0.13):
    rt = [p for p in res["tune"] if p["filter"] == "raw"][0]
    g = sweep.best_at(res["tune"], "gpb1", rt["jitter"] * share)
    print(f"tune {share}: {g['setting']} rmse {g['rmse_moving']:.3f}")
    for label in ("tune", "held"):
        P = res[label]; raw = [p for p in P if p["filter"] == "raw"][0]
        mine = [p for p in P if p["filter"] == "gpb1" and p["setting"] == g["setting"]][0]
        e = sweep.best_at(P, "1 euro", mine["jitter"])
        print(f"   {label}: jitter {100*mine['jitter']/raw['jitter']:.1f}% rmse {mine['rmse_moving']:.3f} ov {100*mine['overshoot_share']:.1f}% onset {mine['onset_ms']:.0f} ms | euro {e['rmse_moving']:.3f} ({e['setting']}) ratio {mine['rmse_moving']/e['rmse_moving']:.2f}")
