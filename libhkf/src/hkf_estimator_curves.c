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
 * of its own, so firmware that does not name them does not link them.
 */
#include "hkf/hkf.h"

/* 1,386 faces found of 1,475 within +-99 deg; count-weighted RMS residual 0.73 / 0.88 / 0.67 deg */
const hkf_noise_curve_t hkf_noise_mesh_pnp[3] = {
    {HKF_REAL(10002.921), HKF_REAL(10000.0), HKF_REAL(-2.092), HKF_REAL(688.07)},
    {HKF_REAL(10001.931), HKF_REAL(9999.999), HKF_REAL(-5.515), HKF_REAL(1391.36)},
    {HKF_REAL(29.637), HKF_REAL(27.126), HKF_REAL(0.94), HKF_REAL(34.82)},
};

/* 1,475 of 1,475 (label-box crops); residual 1.26 / 0.47 / 1.96 deg */
const hkf_noise_curve_t hkf_noise_whenet[3] = {
    {HKF_REAL(10002.981), HKF_REAL(10000.0), HKF_REAL(-4.72), HKF_REAL(748.61)},
    {HKF_REAL(4.517), HKF_REAL(1.055), HKF_REAL(5.016), HKF_REAL(20.49)},
    {HKF_REAL(10001.315), HKF_REAL(10000.0), HKF_REAL(-1.592), HKF_REAL(819.28)},
};
