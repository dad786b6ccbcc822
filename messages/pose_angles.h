/*
 * pose_angles.h - the angle convention's two small rules, written once for the programs (docs/programs.md,
 * "Angle convention"): an angle the short way round, in [-180, 180), and a pose as seen from its centre.
 */
#ifndef POSE_ANGLES_H
#define POSE_ANGLES_H

#include "hkf_head_pose_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/* deg in [-180, 180): the difference of two angles, or an angle, the short way round. */
double pose_angle_wrap(double degrees);

/* The pose from its centre: pitch, yaw and roll minus the centre's, each the short way round (deg), and
 * x, y, z minus the centre position (cm). */
void pose_from_center(const hkf_head_pose_t *pose, double angles[3], double position[3]);

#ifdef __cplusplus
}
#endif

#endif /* POSE_ANGLES_H */
