/* opentrack_packet.c - see opentrack_packet.h. */
#include "opentrack_packet.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

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
    static const char *const names[OPENTRACK_AXES] = {"yaw", "pitch", "roll"};
    int a;
    for (a = 0; a < OPENTRACK_AXES; ++a) {
        if (strcmp(name, names[a]) == 0) {
            return a;
        }
    }
    return -1;
}

/* [-180, 180): yaw relative to the centre takes the short way round. */
static double wrap_degrees(double angle)
{
    double wrapped = fmod(angle + 180.0, 360.0);
    if (wrapped < 0.0) {
        wrapped += 360.0;
    }
    return wrapped - 180.0;
}

int opentrack_pose_values(const opentrack_mapping_t *mapping, const hkf_head_pose_t *pose,
                          double values[OPENTRACK_FIELDS])
{
    /* hkf's (pitch, yaw, roll), relative to kappa if asked */
    double pitch = pose->pitch, yaw = pose->yaw, roll = pose->roll;
    double angle[OPENTRACK_AXES];
    const float given[6] = {pose->pitch, pose->yaw, pose->roll, pose->center[0], pose->center[1], pose->center[2]};
    int a, i;
    for (i = 0; i < 6; ++i) {
        if (isfinite(given[i]) && fabs((double)given[i]) > OPENTRACK_MAX_ABS_ANGLE) {
            return -2;
        }
    }
    if (mapping->relative_to_center) {
        pitch -= pose->center[0];
        yaw = wrap_degrees(yaw - (double)pose->center[1]);
        roll -= pose->center[2];
    }
    /* the convention mapping (opentrack_packet.h): roll changes sign */
    angle[OPENTRACK_AXIS_YAW] = yaw;
    angle[OPENTRACK_AXIS_PITCH] = pitch;
    angle[OPENTRACK_AXIS_ROLL] = -roll;
    values[OPENTRACK_X] = values[OPENTRACK_Y] = values[OPENTRACK_Z] = 0.0;
    for (a = 0; a < OPENTRACK_AXES; ++a) {
        values[OPENTRACK_YAW + a] = (mapping->invert[a] ? -angle[a] : angle[a]) * mapping->scale[a];
    }
    for (i = 0; i < OPENTRACK_FIELDS; ++i) {
        if (!isfinite(values[i])) {
            return -1;
        }
    }
    return 0;
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
