#!/usr/bin/env bash
# hkf-estimator --dataset with no --model measures the default pipeline (the mesh, WHENet where
# the live pipeline runs it, fused as hkf-filter fuses one frame), and its per-bin figures are
# dev/eval/fusion_on_aflw.py's "pipeline" row, computed from each model measured alone
# (--second-model none) on the same real AFLW2000 images.
# usage: dataset_pipeline_test.sh BUILD_DIR SOURCE_DIR PYTHON AFLW2000_DIR [LIMIT]
set -euo pipefail
build=$1 source=$2 python=$3 data=$4 limit=${5:-120}
est=$build/estimator/hkf-estimator
[ -s "$data/labels.csv" ] || { echo "SKIP: no $data/labels.csv"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$est" --dataset "$data" --limit "$limit" --predictions "$work/pipeline.csv" >"$work/pipeline.txt" 2>"$work/err.txt" \
  || { cat "$work/err.txt"; fail "the default --dataset run"; }
cat "$work/pipeline.txt"
grep -q "^the default pipeline (mesh_pnp; whenet where" "$work/pipeline.txt" || fail "no --model does not measure the default pipeline"
for m in mesh_pnp whenet; do
  "$est" --dataset "$data" --limit "$limit" --model "$m" --second-model none --predictions "$work/$m.csv" >"$work/$m.txt" \
    2>/dev/null || fail "--model $m --second-model none"
  grep -q "^$m on " "$work/$m.txt" || fail "--model $m --second-model none does not measure $m alone"
done
"$python" "$source/dev/eval/fusion_on_aflw.py" --labels "$data/labels.csv" --mesh "$work/mesh_pnp.csv" \
  --whenet "$work/whenet.csv" --limit "$limit" --filter "$build/tools/hkf-filter" >"$work/fusion.txt" || fail "fusion_on_aflw.py"
"$python" - "$work/pipeline.txt" "$work/fusion.txt" <<'PY' || fail "the estimator's figures are not fusion_on_aflw.py's pipeline row"
import re
import sys
ours = re.findall(r"labelled \|yaw\| +\d+-\d+ deg: +\d+ images, +\d+ faces found \( *([\d.]+) %\).*mean ([\d.]+)",
                  open(sys.argv[1]).read())
row = next(l for l in open(sys.argv[2]) if l.startswith("| the pipeline"))
theirs = re.findall(r"([\d.]+) %, ([\d.]+)°", row)[:3]
assert len(ours) == 3 and len(theirs) == 3, (ours, theirs)
for (found, mae), (found2, mae2) in zip(ours, theirs):
    # the same faces; the MAE to 0.01 deg (fusion_on_aflw.py reads predictions rounded to 1e-4 deg)
    assert found == found2 and abs(float(mae) - float(mae2)) <= 0.011, (ours, theirs)
print("dataset_pipeline_test: per bin (found %, mean MAE):", ours, "= fusion_on_aflw.py's pipeline row", theirs)
PY
