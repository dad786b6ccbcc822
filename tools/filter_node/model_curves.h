/*
 * model_curves.h - Eq. 8 curves (tau lambda mu sigma, deg) of the estimators
 * hkf ships, fitted as the paper's Table I was: dev/fit/fit_noise_curves.py
 * on hkf-estimator --dataset's predictions for ../shared/data/aflw2000 (the
 * 1,500-image dev split). hkf-filter knows them as built-in models, beside
 * libhkf's FSA-Net and Hopenet presets.
 */
#ifndef MODEL_CURVES_H
#define MODEL_CURVES_H

#include "hkf/hkf.h"

extern const hkf_noise_curve_t model_curves_mesh_pnp[3];
extern const hkf_noise_curve_t model_curves_whenet[3];

#endif /* MODEL_CURVES_H */
