/*
 * model_pairing.h - the rule that pairs two estimator models on one channel, one
 * constant for the two programs that apply it: hkf-estimator (frame_fusion.hpp:
 * which frames it asks the second model for, and which it fuses) and hkf-filter
 * (its config's pair_second_alone_from_yaw default: where a paired frame takes
 * the second model's measurement alone). Chosen on AFLW2000's even images
 * (docs/programs.md).
 */
#ifndef MODEL_PAIRING_H
#define MODEL_PAIRING_H

/* deg: where the first model measures |yaw| at least this, a frame the second model also
 * measured takes the second's measurement alone; below it both are fused. */
#define HKF_SECOND_ALONE_FROM_YAW 25.0

#endif /* MODEL_PAIRING_H */
