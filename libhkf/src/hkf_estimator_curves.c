/*
 * hkf_estimator_curves.c - the Eq. 8 curves of the estimators hkf ships (hkf.h:
 * hkf_noise_mesh_pnp, hkf_noise_whenet), fitted as the paper's Table I was:
 * dev/fit/fit_noise_curves.py on hkf-estimator --dataset's predictions for the
 * 1,500-image AFLW2000 development split. Reproduce with:
 *   build/estimator/hkf-estimator --dataset ../shared/data/aflw2000 --model NAME --second-model none \
 *       --predictions p.csv
 *   .venv/bin/python dev/fit/fit_noise_curves.py --labels ../shared/data/aflw2000/labels.csv \
 *       --predictions p.csv --model NAME --png NAME.png
 * (tests/fit/fit_test.sh does, and checks these numbers.) lambda = 1e4 marks an
 * axis whose error grows quadratically over the whole range: only
 * lambda / sigma^2 is determined there, and lambda is held at r_max. A source
 * of its own, so firmware that does not name them does not link them. Written with
 * HKF_NOISE_CURVE, which suits every numeric build (Q16.16 holds a curve as its
 * floor and curvature: tests/libhkf/test_equations.c checks them in each build).
 */
#include "hkf/hkf.h"

/* 1,386 faces found of 1,475 within +-99 deg; count-weighted RMS residual 0.73 / 0.88 / 0.67 deg */
const hkf_noise_curve_t hkf_noise_mesh_pnp[3] = {
    HKF_NOISE_CURVE(10002.921, 10000.0, -2.092, 688.07),
    HKF_NOISE_CURVE(10001.931, 9999.999, -5.515, 1391.36),
    HKF_NOISE_CURVE(29.637, 27.126, 0.94, 34.82),
};

/* 1,475 of 1,475 (label-box crops); residual 1.26 / 0.47 / 1.96 deg */
const hkf_noise_curve_t hkf_noise_whenet[3] = {
    HKF_NOISE_CURVE(10002.981, 10000.0, -4.72, 748.61),
    HKF_NOISE_CURVE(4.517, 1.055, 5.016, 20.49),
    HKF_NOISE_CURVE(10001.315, 10000.0, -1.592, 819.28),
};
