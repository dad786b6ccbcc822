#!/usr/bin/env bash
# hkf-estimator's evaluation mode on real data: WHENet on the labelled face boxes, the mesh on the live path,
# and both fused as hkf-filter fuses them (the first 100 AFLW2000 images; an inference test, in the optimised
# build: its error paths and levels are estimator_cli_test.sh's, under the sanitizers).
# usage: estimator_dataset_test.sh BUILD_DIR SOURCE_DIR DATA_DIR
set -euo pipefail
build=$1 source=$2 data=$3
est=$build/estimator/hkf-estimator
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# real data: the first 100 AFLW2000 images; WHENet on the labelled face boxes, as its paper measured it
"$est" --dataset "$data" --crop labels --predictions "$work/p.csv" --limit 100 --model whenet | tee "$work/out.txt"
[ "$(wc -l <"$work/p.csv")" -eq 101 ] || fail "expected 100 predictions"
head -1 "$work/p.csv" | grep -qx "image,pitch_deg,yaw_deg,roll_deg" || fail "CSV header"
read -r pitch yaw roll < <(sed -n 's/MAE deg: pitch \([0-9.]*\), yaw \([0-9.]*\), roll \([0-9.]*\).*/\1 \2 \3/p' "$work/out.txt")
awk -v p="$pitch" -v y="$yaw" -v r="$roll" 'BEGIN { exit !(p < 6.5 && y < 6.5 && r < 6.5) }' ||
  fail "MAE $pitch/$yaw/$roll deg is far from WHENet's published ~5.4"

grep -q "(labelled face boxes): 100 images (0 unreadable, 0 without a face found)" "$work/out.txt" ||
  fail "WHENet given the labelled boxes must take every face"

# the default estimator on the same images, the default way: the live path (detector on the whole image)
"$est" --dataset "$data" --predictions "$work/m.csv" --limit 100 --model mesh_pnp --second-model none | tee "$work/mesh.txt"
grep -q "(live path: detector on the whole image)" "$work/mesh.txt" || fail "--dataset does not default to the live path"
grep -q "^faces not found: [0-9]*, of which the detector took another face: [0-9]*$" "$work/mesh.txt" ||
  fail "no count of faces not found on the live path"
read -r pitch yaw roll < <(sed -n 's/MAE deg: pitch \([0-9.]*\), yaw \([0-9.]*\), roll \([0-9.]*\).*/\1 \2 \3/p' "$work/mesh.txt")
awk -v p="$pitch" -v y="$yaw" -v r="$roll" 'BEGIN { exit !(p < 7 && y < 7 && r < 7) }' || fail "mesh_pnp MAE $pitch/$yaw/$roll deg"
missed=$(sed -n 's/.*, \([0-9]*\) without a face found.*/\1/p' "$work/mesh.txt")
[ "$missed" -le 20 ] || fail "mesh_pnp found no face in $missed of 100 images"
# by labelled yaw: three bins whose found faces add up to the images evaluated
[ "$(grep -c '^labelled |yaw| .* faces found' "$work/mesh.txt")" = 3 ] || fail "no per-yaw-bin lines"
found=$(sed -n 's/^labelled |yaw| .* images, *\([0-9]*\) faces found.*/\1/p' "$work/mesh.txt" | awk '{ s += $1 } END { print s }')
evaluated=$(sed -n 's/.* \([0-9]*\) within +-99 deg$/\1/p' "$work/mesh.txt")
[ "$found" = "$evaluated" ] || fail "the yaw bins hold $found faces, $evaluated were evaluated"

# both models' predictions fused as hkf_update_pair fuses them (dev/eval/fusion_on_aflw.py): every face
# either model found is estimated, and the fused error lies between the two models' (per image it is a
# weighted mean of theirs, so far below the worse one)
"$source/.venv/bin/python" "$source/dev/eval/fusion_on_aflw.py" --labels "$data/labels.csv" --limit 100 --mesh "$work/m.csv" \
  --whenet "$work/p.csv" --filter "$build/tools/hkf-filter" | tee "$work/fusion.txt"
"$source/.venv/bin/python" - "$work/fusion.txt" <<'PY' || fail "fusion_on_aflw.py"
import re, sys
rows = {m[1]: (float(m[2]), float(m[3])) for m in re.finditer(r"^\| (.+?) \|.*\| ([\d.]+) %, ([\d.]+)° \|$", open(sys.argv[1]).read(), re.M)}
mesh, whenet, fused = rows["mesh_pnp"], rows["whenet"], next(v for k, v in rows.items() if k.startswith("fused"))
assert fused[0] >= max(mesh[0], whenet[0]), (fused, mesh, whenet)
assert fused[1] < max(mesh[1], whenet[1]), (fused, mesh, whenet)
# the pipeline's row (mesh, WHENet fused in or alone at larger yaw): every face either found, and better than the worse
pipeline = next(v for k, v in rows.items() if k.startswith("the pipeline"))
assert pipeline[0] == fused[0] and pipeline[1] < max(mesh[1], whenet[1]), (pipeline, mesh, whenet)
PY

echo "estimator_dataset_test: all checks passed"
