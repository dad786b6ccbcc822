#!/usr/bin/env bash
# The Table I procedure (dev/fit) on real data: hkf-estimator --dataset on the
# shared AFLW2000 split, then fit_noise_curves.py. The fit must be plausible
# (error lowest near 0 deg, rising toward +-90 deg, small residual) and, for
# the default estimator, reproduce the curves built into hkf-filter.
# usage: fit_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd)
python=$source/.venv/bin/python data=$source/../shared/data/aflw2000
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# fit MODEL [LIMIT]: predictions, then the fit and its PNG
fit() {
  "$build/estimator/hkf-estimator" --dataset "$data" --crop labels --model "$1" --second-model none ${2:+--limit "$2"} --predictions "$work/$1.csv" \
    >"$work/$1_eval.txt" 2>&1 || { cat "$work/$1_eval.txt" >&2; fail "hkf-estimator --dataset --model $1"; }
  "$python" "$source/dev/fit/fit_noise_curves.py" --labels "$data/labels.csv" --predictions "$work/$1.csv" \
    --model "$1" --png "$work/$1.png" >"$work/$1_fit.txt" || fail "fit_noise_curves.py for $1"
  cat "$work/$1_fit.txt"
  file "$work/$1.png" | grep -q "PNG image" || fail "no PNG for $1"
}

# plausible FILE: for every axis, the error at mu is 1-8 deg, the curve at +-90 deg
# above it, mu within 10 deg of 0 unless the curve is nearly flat (under 3 deg
# deep: then mu means little), and the count-weighted residual under 2.5 deg
plausible() {
  "$python" - "$1" <<'PY' || fail "implausible fit in $1"
import re
import sys
text = open(sys.argv[1]).read()
for axis in ("pitch", "yaw", "roll"):
    m = re.search(rf"  {axis}: tau \S+, lambda \S+, mu (\S+), sigma \S+; error at mu (\S+) deg, at -90/\+90 (\S+)/(\S+) deg; "
                  r"residual \(count-weighted RMS\) (\S+) deg", text)
    mu, at_mu, low, high, residual = float(m[1]), float(m[2]), float(m[3]), float(m[4]), float(m[5])
    assert 1.0 <= at_mu <= 8.0 and (abs(mu) <= 10.0 or max(low, high) - at_mu < 3.0), (axis, mu, at_mu)
    assert low > at_mu and high > at_mu and residual <= 2.5, (axis, low, high, residual)
    print(f"fit_test: {axis}: error {at_mu} deg at mu {mu} deg, {low}/{high} deg at -90/+90, residual {residual} deg")
PY
}

fit mesh_pnp
plausible "$work/mesh_pnp_fit.txt"
# the built-in mesh_pnp curves are this fit's (hkf-filter --print-config prints them)
"$build/tools/hkf-filter" --print-config >"$work/config.txt"
"$python" - "$work/mesh_pnp_fit.txt" "$work/config.txt" <<'PY' || fail "the built-in mesh_pnp curves are not this fit's"
import re
import sys
fit = open(sys.argv[1]).read()
config = open(sys.argv[2]).read().split("[model mesh_pnp]")[1]
for axis in ("pitch", "yaw", "roll"):
    fitted = [float(v) for v in re.search(rf"^noise\.{axis}\s*=\s*([^\n#]+)", fit, re.M)[1].split()]
    built_in = [float(v) for v in re.search(rf"^noise\.{axis}\s*=\s*([^\n#]+)", config, re.M)[1].split()]
    # tau - lambda to 0.01 deg, mu to 0.01 deg, sigma to 0.1 %
    assert abs((fitted[0] - fitted[1]) - (built_in[0] - built_in[1])) <= 0.01, (axis, fitted, built_in)
    assert abs(fitted[2] - built_in[2]) <= 0.01 and abs(fitted[3] / built_in[3] - 1) <= 1e-3, (axis, fitted, built_in)
print("fit_test: the built-in mesh_pnp curves reproduce")
PY
# WHENet is slow in OpenCV's DNN: 300 images are enough to check the procedure on it
fit whenet 300
plausible "$work/whenet_fit.txt"
echo "fit_test: all checks passed"
