/* node_pose.c - see node_pose.h. */
#include "node_pose.h"

#include <string.h>

/* A posterior at utime older than the pose published before it (--rate's ticks went past a late frame):
 * moved on to that pose's time (hkf_extrapolate), so that no pose is stamped earlier than the one before. */
static void not_before_published(filter_node_t *node, const hkf_output_t **out, int64_t *utime, hkf_output_t *moved)
{
    if (*utime < node->published_utime &&
        hkf_extrapolate(&node->filter, (hkf_real_t)(((double)node->published_utime - (double)*utime) * 1e-6), moved) ==
            HKF_OK) {
        *out = moved;
        *utime = node->published_utime;
    }
}

void node_pose_fill(filter_node_t *node, const hkf_output_t *out, int64_t utime, hkf_head_pose_t *pose)
{
    hkf_real_t center[3] = {0, 0, 0};
    hkf_output_t moved;
    int a;
    not_before_published(node, &out, &utime, &moved);
    node->published_utime = utime;
    memset(pose, 0, sizeof *pose);
    pose->utime = utime;
    pose->measurement_utime = node->last_measurement_utime;
    pose->seq = ++node->seq;
    pose->status = out->status == HKF_STATUS_TRACKING   ? HKF_HEAD_POSE_T_TRACKING
                   : out->status == HKF_STATUS_COASTING ? HKF_HEAD_POSE_T_COASTING
                                                        : HKF_HEAD_POSE_T_LOST;
    pose->pitch = out->angle[HKF_AXIS_PITCH];
    pose->yaw = out->angle[HKF_AXIS_YAW];
    pose->roll = out->angle[HKF_AXIS_ROLL];
    pose->pitch_rate = out->rate[HKF_AXIS_PITCH];
    pose->yaw_rate = out->rate[HKF_AXIS_YAW];
    pose->roll_rate = out->rate[HKF_AXIS_ROLL];
    for (a = 0; a < 3; ++a) {
        pose->variance[a] = out->variance[a];
        pose->r[a] = out->r[a];
    }
    (void)hkf_get_center(&node->filter, center); /* set by the first measurement, so always there once posing */
    pose->center[0] = (float)center[HKF_AXIS_PITCH];
    pose->center[1] = (float)center[HKF_AXIS_YAW];
    pose->center[2] = (float)center[HKF_AXIS_ROLL];
    pose->loop_closure_active = (out->flags & HKF_FLAG_LOOP_CLOSURE) != 0;
    pose->extrapolated = (out->flags & HKF_FLAG_EXTRAPOLATED) != 0;
    pose->latency_us = 0;
    node_position_fill(&node->position, utime, pose);
    ++node->counts.published;
}
