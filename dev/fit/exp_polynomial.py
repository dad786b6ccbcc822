#!/usr/bin/env python3
"""The polynomial the estimator's swish takes exp(r) by (layer_kernels_impl.hpp, exp_approx).

After the range reduction t = k ln2 + r, r lies in [-ln2/2, ln2/2]; a degree-5 polynomial of least
relative error there (Lawson's iteration of weighted least squares on Chebyshev points) is 7.5e-8 off
at most, against 1.2e-7 for the Taylor series to r^6, for one fused multiply-add fewer. Prints the
coefficients as float literals and both errors, in exact and in float arithmetic.
usage: dev/fit/exp_polynomial.py
"""
import math
import sys

import numpy as np

DEGREE = 5


def fit(half_width, degree, iterations=60):
    r = np.cos(np.linspace(0.0, np.pi, 4001)) * half_width
    weights = np.ones_like(r)
    design = np.vander(r, degree + 1, increasing=True) / np.exp(r)[:, None]  # relative error
    for _ in range(iterations):
        root = np.sqrt(weights)
        coefficients, *_ = np.linalg.lstsq(design * root[:, None], root, rcond=None)
        error = np.abs(design @ coefficients - 1.0)
        weights = weights * error
        weights /= weights.sum()
    return coefficients, float(error.max())


def float_error(coefficients, half_width):
    r = np.linspace(-half_width, half_width, 200001).astype(np.float32)
    c = coefficients.astype(np.float32)
    p = np.full_like(r, c[-1])
    for k in range(len(c) - 2, -1, -1):
        p = (p * r + c[k]).astype(np.float32)
    return float(np.max(np.abs(p.astype(np.float64) / np.exp(r.astype(np.float64)) - 1.0)))


def main():
    if len(sys.argv) > 1:
        print(__doc__.strip())
        return 0 if sys.argv[1] in ("-h", "--help") else 2
    half_width = np.log(2.0) / 2.0
    coefficients, exact = fit(half_width, DEGREE)
    print("coefficients, r^0 first:", ", ".join("%.9ef" % np.float32(c) for c in coefficients))
    print(f"largest relative error on [-ln2/2, ln2/2]: {exact:.2e} exact, {float_error(coefficients, half_width):.2e} in float")
    taylor = np.array([1.0 / math.factorial(k) for k in range(7)])
    print(f"the Taylor series to r^6: {float_error(taylor, half_width):.2e} in float")
    return 0


if __name__ == "__main__":
    sys.exit(main())
