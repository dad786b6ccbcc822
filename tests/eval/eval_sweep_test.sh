#!/usr/bin/env bash
# dev/eval/evaluate.py end to end on one real clip through mesh_pnp: every
# filter's sweep runs, the tables and the plot are written, and each filter's
# jitter-lag curve behaves as a smoother should (more smoothing: less jitter,
# more lag) on real head motion.
# usage: eval_sweep_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd)
out=$build/eval_test
rm -rf "$out"
"$source/.venv/bin/python" "$source/dev/eval/evaluate.py" --build "$build" --out "$out" --estimators mesh_pnp \
  --clips 1 | tee "$out.log"
for f in sweep.csv curves.csv equal_jitter.md jitter_lag.png; do
  [ -s "$out/$f" ] || { echo "FAIL: no $out/$f" >&2; exit 1; }
done
"$source/.venv/bin/python" - "$out/curves.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
def curve(name, key):
    pts = sorted((key(r["setting"]), float(r["jitter"]), float(r["lag_ms"])) for r in rows if r["filter"] == name)
    return pts
checks = {
    "hkf adaptive R": curve("hkf adaptive R", lambda s: -float(s.split("x")[1])),   # less q: more smoothing
    "EWMA": curve("EWMA", lambda s: float(s.split()[1])),                         # more max_smoothing
}
failed = False
for name, pts in checks.items():
    first, last = pts[0], pts[-1]
    ok = last[1] < first[1] and last[2] > first[2]
    print(f"{'OK  ' if ok else 'FAIL'} {name}: jitter {first[1]:.3f} -> {last[1]:.3f} deg, lag {first[2]:.0f} -> {last[2]:.0f} ms "
          f"from the least to the most smoothing")
    failed |= not ok
sys.exit(1 if failed else 0)
PY
