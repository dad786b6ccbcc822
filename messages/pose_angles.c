/* pose_angles.c - see pose_angles.h. */
#include "pose_angles.h"

#include <math.h>

double pose_angle_wrap(double degrees)
{
    double wrapped = fmod(degrees + 180.0, 360.0); /* exact: fmod rounds nothing */
    if (wrapped < 0.0) {
        wrapped += 360.0;
    }
    return wrapped - 180.0;
}

void pose_from_center(const hkf_head_pose_t *pose, double angles[3], double position[3])
{
    const float angle[3] = {pose->pitch, pose->yaw, pose->roll}, place[3] = {pose->x, pose->y, pose->z};
    int a;
    for (a = 0; a < 3; ++a) {
        angles[a] = pose_angle_wrap((double)angle[a] - (double)pose->center[a]);
        position[a] = (double)place[a] - (double)pose->position_center[a];
    }
}
