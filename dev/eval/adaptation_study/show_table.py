import os, pickle, sys
OUT_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', '..', 'out', 'eval', 'adaptation_study')
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import sweep
res = pickle.load(open(os.path.join(OUT_DIR, "sweep.pkl"), "rb"))
rt = [p for p in res["tune"] if p["filter"] == "raw"][0]; rh = [p for p in res["held"] if p["filter"] == "raw"][0]
H = {p["setting"]: p for p in res["held"] if p["filter"] == "gpb1"}
for p in sorted([p for p in res["tune"] if p["filter"] == "gpb1"], key=lambda p: p["jitter"]):
    e = sweep.best_at(res["tune"], "1 euro", p["jitter"]); h = H[p["setting"]]; eh = sweep.best_at(res["held"], "1 euro", h["jitter"])
    print(f"{p['setting']:32s} tune j {100*p['jitter']/rt['jitter']:5.1f}% rmse {p['rmse_moving']:.3f} ratio {p['rmse_moving']/e['rmse_moving'] if e else float('nan'):.2f} ov {100*p['overshoot_share']:.1f} | held j {100*h['jitter']/rh['jitter']:5.1f}% rmse {h['rmse_moving']:.3f} ratio {h['rmse_moving']/eh['rmse_moving'] if eh else float('nan'):.2f} ov {100*h['overshoot_share']:.1f}")
