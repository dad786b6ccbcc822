/* opentrack_packet.c - see opentrack_packet.h. */
#include "opentrack_packet.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "pose_angles.h"

opentrack_mapping_t opentrack_default_mapping(void)
{
    opentrack_mapping_t m;
    int a;
    memset(&m, 0, sizeof m);
    m.relative_to_center = 1;
    for (a = 0; a < OPENTRACK_AXES; ++a) {
        m.scale[a] = 1.0;
    }
    return m;
}

int opentrack_axis_from_name(const char *name)
{
    static const char *const names[OPENTRACK_AXES] = {"yaw", "pitch", "roll", "x", "y", "z"};
    int a;
    for (a = 0; a < OPENTRACK_AXES; ++a) {
        if (strcmp(name, names[a]) == 0) {
            return a;
        }
    }
    return -1;
}

/* x within [-limit, limit] */
static double within(double x, double limit) { return x > limit ? limit : x < -limit ? -limit : x; }

int opentrack_pose_values(const opentrack_mapping_t *mapping, const hkf_head_pose_t *pose,
                          double values[OPENTRACK_FIELDS])
{
    /* hkf's (pitch, yaw, roll), relative to kappa if asked */
    double pitch = pose->pitch, yaw = pose->yaw, roll = pose->roll;
    double angle[3];
    const float given[6] = {pose->pitch, pose->yaw, pose->roll, pose->center[0], pose->center[1], pose->center[2]};
    const float place[6] = {pose->x, pose->y, pose->z, pose->position_center[0], pose->position_center[1],
                            pose->position_center[2]};
    double position[3];
    int a, i, position_beyond = 0;
    if (pose->status != HKF_HEAD_POSE_T_TRACKING && pose->status != HKF_HEAD_POSE_T_COASTING &&
        pose->status != HKF_HEAD_POSE_T_LOST) {
        return -4;
    }
    for (i = 0; i < 6; ++i) {
        if (isfinite(given[i]) && fabs((double)given[i]) > OPENTRACK_MAX_ABS_ANGLE) {
            return -2;
        }
        position_beyond |= !isfinite(place[i]) || fabs((double)place[i]) > OPENTRACK_MAX_ABS_POSITION;
    }
    if (mapping->relative_to_center) { /* hkf's camera frame is opentrack's x, y, z */
        double from_center[3];
        pose_from_center(pose, from_center, position);
        pitch = from_center[0], yaw = from_center[1], roll = from_center[2];
    } else {
        for (i = 0; i < 3; ++i) {
            position[i] = (double)place[i];
        }
    }
    /* the convention mapping (opentrack_packet.h): roll changes sign */
    angle[OPENTRACK_AXIS_YAW] = yaw;
    angle[OPENTRACK_AXIS_PITCH] = pitch;
    angle[OPENTRACK_AXIS_ROLL] = -roll;
    for (i = 0; i < 6; ++i) {
        if (!isfinite(given[i])) {
            return -1;
        }
    }
    for (a = 0; a < 3; ++a) { /* scaled, then within what opentrack's axes show */
        values[OPENTRACK_YAW + a] =
            within((mapping->invert[a] ? -angle[a] : angle[a]) * mapping->scale[a], OPENTRACK_MAX_ABS_ANGLE);
        if (!position_beyond) {
            values[OPENTRACK_X + a] = within((mapping->invert[OPENTRACK_AXIS_X + a] ? -position[a] : position[a]) *
                                                 mapping->scale[OPENTRACK_AXIS_X + a],
                                             OPENTRACK_MAX_ABS_POSITION);
        }
    }
    return position_beyond ? -3 : 0;
}

hkf_head_pose_t opentrack_predict(const hkf_head_pose_t *pose, double horizon)
{
    hkf_head_pose_t moved = *pose;
    if (pose->status == HKF_HEAD_POSE_T_LOST || !(horizon > 0.0 && isfinite(horizon))) {
        return moved;
    }
    moved.pitch = (float)pose_angle_wrap((double)pose->pitch + (double)pose->pitch_rate * horizon);
    moved.yaw = (float)pose_angle_wrap((double)pose->yaw + (double)pose->yaw_rate * horizon);
    moved.roll = (float)pose_angle_wrap((double)pose->roll + (double)pose->roll_rate * horizon);
    if (pose->z > 0.f) { /* a position measured */
        const double z = (double)pose->z + (double)pose->z_rate * horizon;
        moved.x = (float)((double)pose->x + (double)pose->x_rate * horizon);
        moved.y = (float)((double)pose->y + (double)pose->y_rate * horizon);
        moved.z = (float)(z > OPENTRACK_MIN_Z ? z : OPENTRACK_MIN_Z);
    }
    return moved;
}

double opentrack_horizon(const hkf_head_pose_t *pose, int64_t now_us, double lead_s)
{
    const double age = ((double)now_us - (double)pose->utime) * 1e-6; /* stamps may be anything */
    return age >= 0.0 && age <= OPENTRACK_MAX_AGE ? age + lead_s : 0.0;
}

void opentrack_encode(const double values[OPENTRACK_FIELDS], unsigned char packet[OPENTRACK_PACKET_SIZE])
{
    int i, b;
    for (i = 0; i < OPENTRACK_FIELDS; ++i) {
        uint64_t bits;
        memcpy(&bits, &values[i], sizeof bits);
        for (b = 0; b < 8; ++b) {
            packet[8 * i + b] = (unsigned char)(bits >> (8 * b));
        }
    }
}
