/* node_position.c - see node_position.h. */
#include "node_position.h"

#include <math.h>
#include <string.h>

#include "hkf/hkf.h"

/* Seconds from the last position taken to capture time utime, 0 when utime is not later
 * (stamps may be anything: in double). */
static double position_ahead(const node_position_t *p, int64_t utime)
{
    const double ahead = ((double)utime - (double)p->utime) * 1e-6;
    return ahead > 0.0 ? ahead : 0.0;
}

void node_position_fill(const node_position_t *p, int64_t utime, hkf_head_pose_t *pose)
{
    float *position[3] = {&pose->x, &pose->y, &pose->z}, *rate[3] = {&pose->x_rate, &pose->y_rate, &pose->z_rate};
    hkf_position_output_t out;
    hkf_position_state_t state;
    int a;
    if (hkf_position_extrapolate(&p->filter, (hkf_real_t)position_ahead(p, utime), &out) != HKF_OK ||
        hkf_position_get_state(&p->filter, &state) != HKF_OK) {
        return; /* all 0: no position measured yet */
    }
    for (a = 0; a < 3; ++a) {
        *position[a] = (float)out.position[a];
        *rate[a] = (float)out.rate[a];
        pose->position_variance[a] = (float)out.variance[a];
        pose->position_center[a] = (float)state.center[a];
    }
    pose->position_status = out.status == HKF_STATUS_TRACKING   ? HKF_HEAD_POSE_T_TRACKING
                            : out.status == HKF_STATUS_COASTING ? HKF_HEAD_POSE_T_COASTING
                                                                : HKF_HEAD_POSE_T_LOST;
    if (pose->z < FILTER_NODE_MIN_Z) {
        pose->z = FILTER_NODE_MIN_Z; /* a coast toward the camera stops at it */
    }
}

/* A measurement's position xyz (valid: it found a face): 1 when it is one the node takes
 * (FILTER_NODE_MIN_Z <= z and every axis within HKF_MAX_ABS_POSITION), 0 when there is none (no face,
 * or z = 0: not measured), -1 when it is a bad one (non-finite, z < 0 or too near, beyond the range). */
static int position_of(int valid, const float xyz[3])
{
    const float most = (float)HKF_MAX_ABS_POSITION;
    if (!valid || xyz[2] == 0.f) {
        return 0;
    }
    return isfinite(xyz[0]) && isfinite(xyz[1]) && isfinite(xyz[2]) && fabsf(xyz[0]) <= most &&
                   fabsf(xyz[1]) <= most && xyz[2] >= FILTER_NODE_MIN_Z && xyz[2] <= most
               ? 1
               : -1;
}

/* A position xyz measured at utime (R scaled by r_scale) into the position filter, if later than the last. */
static node_position_result_t update_position(node_position_t *p, const float xyz[3], int64_t utime, float r_scale)
{
    const hkf_real_t z[3] = {xyz[0], xyz[1], xyz[2]};
    hkf_position_output_t out;
    /* the first position's dt is unused; a gap beyond max_dt restarts the track in hkf_position_update */
    const double dt = hkf_position_started(&p->filter) ? ((double)utime - (double)p->utime) * 1e-6 : 0.02;
    int gated;
    if (!(dt > 0.0) || hkf_position_update(&p->filter, z, (hkf_real_t)r_scale, (hkf_real_t)dt, &out) != HKF_OK) {
        return NODE_POSITION_NONE;
    }
    p->utime = utime;
    gated = (out.flags & HKF_FLAG_GATED) != 0;
    /* n for the next position's R; a refused one breaks the second difference */
    (void)hkf_calibration_update_position(&p->calibration, &p->filter, gated ? NULL : z, (hkf_real_t)dt);
    return gated ? NODE_POSITION_GATED : NODE_POSITION_TAKEN;
}

node_position_result_t node_position_take_first(node_position_t *p, const hkf_head_pose_measurement_t *m,
                                                float r_scale)
{
    const float xyz[3] = {m->x, m->y, m->z};
    const int measured = position_of(m->valid, xyz);
    if (measured == 0) {
        (void)hkf_calibration_update_position(&p->calibration, &p->filter, NULL, 0); /* a frame without one */
    }
    if (measured < 0) {
        return NODE_POSITION_BAD;
    }
    return measured > 0 ? update_position(p, xyz, m->utime, r_scale) : NODE_POSITION_NONE;
}

node_position_result_t node_position_take_second(node_position_t *p, const hkf_head_pose_measurement_t *m,
                                                 const second_model_frame_t *frame, float r_scale)
{
    const float xyz[3] = {m->x, m->y, m->z};
    const int measured = position_of(m->valid, xyz);
    float moved[3];
    int first, a;
    if (measured < 0) {
        return NODE_POSITION_BAD;
    }
    if (measured == 0 || frame == NULL) {
        return NODE_POSITION_NONE;
    }
    first = position_of(frame->valid, frame->xyz) > 0;
    {
        const double difference[3] = {(double)frame->xyz[0] - xyz[0], (double)frame->xyz[1] - xyz[1],
                                      (double)frame->xyz[2] - xyz[2]};
        model_offset_learn(&p->offset, m->model ? m->model : "", first ? difference : NULL, FILTER_NODE_POSITION_ALIGN);
    }
    if (first || p->offset.frames < FILTER_NODE_POSITION_MIN_ALIGN) {
        return NODE_POSITION_NONE; /* both measured it: the offset learnt; or not aligned yet */
    }
    for (a = 0; a < 3; ++a) {
        moved[a] = xyz[a] + (float)p->offset.offset[a];
    }
    return update_position(p, moved, m->utime, r_scale);
}

int node_position_init(node_position_t *p, const hkf_position_settings_t *settings,
                       const hkf_calibration_settings_t *calibration)
{
    int result;
    memset(p, 0, sizeof *p);
    model_offset_init(&p->offset);
    result = hkf_position_init(&p->filter, settings);
    return result != HKF_OK ? result : hkf_calibration_init_position(&p->calibration, calibration, &p->filter);
}

void node_position_restart(node_position_t *p)
{
    hkf_position_restart(&p->filter);
    (void)hkf_calibration_update_position(&p->calibration, &p->filter, NULL, 0); /* the history breaks, n stays */
}

/* The centre: the position last published (at the angles' frame time), as the pose carried it - held
 * or coasting, never nearer than FILTER_NODE_MIN_Z. */
void node_position_recenter(node_position_t *p, int64_t utime)
{
    hkf_head_pose_t published;
    memset(&published, 0, sizeof published);
    node_position_fill(p, utime, &published);
    if (hkf_position_started(&p->filter)) {
        const hkf_real_t center[3] = {published.x, published.y, published.z};
        (void)hkf_position_set_center(&p->filter, center); /* within the range: node_position_fill bounds it */
    }
}

void node_position_reset(node_position_t *p)
{
    const hkf_position_settings_t settings = p->filter.settings;
    const hkf_calibration_settings_t calibration = p->calibration.settings;
    (void)node_position_init(p, &settings, &calibration); /* nothing of before stays: the centre set, the noise,
                                                           * the models' offset (the settings passed at start) */
}
