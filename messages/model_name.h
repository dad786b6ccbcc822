/*
 * model_name.h - the one rule for an estimator model's id, for hkf-estimator
 * (--model), hkf-filter's config ([model NAME], --set model.NAME.KEY) and the
 * message (head_pose_measurement_t.lcm's MODEL_NAME_MAX): 1 to 31 letters,
 * digits, '_' or '-', so that it fits the message and reads back from
 * --print-config.
 */
#ifndef MODEL_NAME_H
#define MODEL_NAME_H

#ifdef __cplusplus
extern "C" {
#endif

/* 1 when name follows the rule. */
int model_name_valid(const char *name);

#ifdef __cplusplus
}
#endif

#endif /* MODEL_NAME_H */
