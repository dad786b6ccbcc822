#!/usr/bin/env bash
# RetinaFace finds turned faces where BlazeFace misses them: the first 60 AFLW2000
# dev-split images labelled |yaw| 60-99 deg (a temporary labels file over the shared
# images), each model through hkf-estimator --dataset's live path (the detector on the
# whole image, the largest face taken) with WHENet, which gives a pose for any face found.
# usage: retina_detector_test.sh BUILD_DIR SHARED_DATA_DIR
set -euo pipefail
build=$1 data=$2/aflw2000
[ -s "$data/labels.csv" ] || { echo "SKIP: no $data"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir "$work/set"
ln -s "$(cd "$data/images" && pwd)" "$work/set/images"
awk -F, 'NR == 1 { print; next }
         { y = $2 < 0 ? -$2 : $2; p = $3 < 0 ? -$3 : $3; r = $4 < 0 ? -$4 : $4 }
         y >= 60 && y <= 99 && p <= 99 && r <= 99 && n < 60 { print; ++n }' "$data/labels.csv" >"$work/set/labels.csv"
found() {  # detector -> faces found of the 60, from the estimator's own per-bin line
  "$build/estimator/hkf-estimator" --dataset "$work/set" --predictions "$work/$1.csv" --model whenet --detector "$1" \
    >"$work/$1.txt" 2>&1 || { cat "$work/$1.txt"; echo "FAIL: hkf-estimator --detector $1" >&2; exit 1; }
  sed -n 's/.*60-99 deg: *\([0-9]*\) images, *\([0-9]*\) faces found.*/\2 \1/p' "$work/$1.txt"
}
read -r retina total < <(found retina)
read -r short _ < <(found short)
echo "labelled |yaw| 60-99 deg, $total images: RetinaFace found $retina, BlazeFace short range $short"
grep "60-99" "$work/retina.txt"
[ "$total" -eq 60 ] || { echo "FAIL: $total images, not 60" >&2; exit 1; }
[ "$retina" -ge 57 ] || { echo "FAIL: RetinaFace found $retina of 60 turned faces (want >= 95 %)" >&2; exit 1; }
[ "$retina" -gt "$short" ] || { echo "FAIL: RetinaFace found no more than BlazeFace ($retina vs $short)" >&2; exit 1; }
