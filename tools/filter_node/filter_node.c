/* filter_node.c - see filter_node.h. */
#include "filter_node.h"

#include <math.h>
#include <string.h>

static int setup_filter(filter_node_t *node, const char *model)
{
    int known;
    const hkf_settings_t s = node_config_for_model(node->config, model, &known);
    if (model != node->model) {
        strncpy(node->model, model, sizeof node->model - 1);
        node->model[sizeof node->model - 1] = '\0';
    }
    const int result = hkf_init(&node->filter, &s);
    return result != HKF_OK ? result : hkf_calibration_init(&node->calibration, &node->config->calibration, &node->filter);
}

int filter_node_init(filter_node_t *node, const node_config_t *config)
{
    int result;
    memset(node, 0, sizeof *node);
    node->config = config;
    second_model_init(&node->second);
    second_position_init(&node->second_position);
    result = hkf_position_init(&node->position, &config->position);
    if (result != HKF_OK) {
        return result; /* cannot happen: the config was checked */
    }
    return setup_filter(node, "");
}

/* Seconds from the last position taken to capture time utime, 0 when utime is not later
 * (stamps may be anything: in double). */
static double position_ahead(const filter_node_t *node, int64_t utime)
{
    const double ahead = ((double)utime - (double)node->position_utime) * 1e-6;
    return ahead > 0.0 ? ahead : 0.0;
}

/* The filtered position at capture time utime (hkf_position_extrapolate): the last one
 * taken moved on by its rate for up to the position's max_dt, then held with rate 0 while
 * its variance grows; within the range the node accepts. */
static void fill_position(const filter_node_t *node, int64_t utime, hkf_head_pose_t *pose)
{
    const hkf_position_filter_t *p = &node->position;
    float *position[3] = {&pose->x, &pose->y, &pose->z}, *rate[3] = {&pose->x_rate, &pose->y_rate, &pose->z_rate};
    hkf_position_output_t out;
    int a;
    if (hkf_position_extrapolate(p, (hkf_real_t)position_ahead(node, utime), &out) != HKF_OK) {
        return; /* all 0: no position measured yet */
    }
    for (a = 0; a < 3; ++a) {
        *position[a] = (float)out.position[a];
        *rate[a] = (float)out.rate[a];
        pose->position_variance[a] = (float)out.variance[a];
        pose->position_center[a] = (float)p->center[a];
    }
    if (pose->z < FILTER_NODE_MIN_Z) {
        pose->z = FILTER_NODE_MIN_Z; /* a coast toward the camera stops at it */
    }
}

/* A measurement's position: 1 when it carries one the node takes (FILTER_NODE_MIN_Z <= z and every
 * axis within HKF_MAX_ABS_POSITION), 0 when it carries none (no face, or z = 0: not measured), -1
 * when it carries a bad one (non-finite, z < 0 or too near, beyond the range). */
static int position_of(const hkf_head_pose_measurement_t *m)
{
    const float most = (float)HKF_MAX_ABS_POSITION;
    if (!m->valid || m->z == 0.f) {
        return 0;
    }
    return isfinite(m->x) && isfinite(m->y) && isfinite(m->z) && fabsf(m->x) <= most && fabsf(m->y) <= most &&
                   m->z >= FILTER_NODE_MIN_Z && m->z <= most
               ? 1
               : -1;
}

/* A position xyz measured at utime (R scaled by r_scale) into the position filter, if later than the last. */
static void update_position(filter_node_t *node, const float xyz[3], int64_t utime, float r_scale)
{
    const hkf_real_t z[3] = {xyz[0], xyz[1], xyz[2]};
    hkf_position_output_t out;
    /* the first position's dt is unused; a gap beyond max_dt restarts the track in hkf_position_update */
    const double dt = hkf_position_started(&node->position) ? ((double)utime - (double)node->position_utime) * 1e-6 : 0.02;
    if (dt > 0.0 && hkf_position_update(&node->position, z, (hkf_real_t)r_scale, (hkf_real_t)dt, &out) == HKF_OK) {
        node->position_utime = utime;
        node->counts.positions_gated += (out.flags & HKF_FLAG_GATED) != 0;
    }
}

/* The first model's frame m: its position (measured, or a bad one counted) into the position
 * filter, and noted for a second model's measurement of the frame. */
static void take_position(filter_node_t *node, const hkf_head_pose_measurement_t *m)
{
    const float xyz[3] = {m->x, m->y, m->z};
    const int mesh = m->model != NULL && strcmp(m->model, FILTER_NODE_MESH_MODEL) == 0;
    const int measured = position_of(m);
    node->counts.bad_positions += measured < 0;
    second_position_note_first(&node->second_position, m->seq, m->utime, measured > 0, xyz);
    if (measured > 0) {
        update_position(node, xyz, m->utime, mesh ? 1.0f : FILTER_NODE_BOX_POSITION_R_SCALE);
    }
}

/* A second model's measurement m: its position stands in where the first model measured none. */
static void take_second_position(filter_node_t *node, const hkf_head_pose_measurement_t *m)
{
    const float xyz[3] = {m->x, m->y, m->z};
    const int measured = position_of(m);
    float moved[3];
    node->counts.bad_positions += measured < 0;
    if (measured > 0 && second_position_take(&node->second_position, m->seq, m->utime, xyz, moved)) {
        update_position(node, moved, m->utime, FILTER_NODE_BOX_POSITION_R_SCALE);
    }
}

static void fill_pose(filter_node_t *node, const hkf_output_t *out, int64_t utime, hkf_head_pose_t *pose)
{
    hkf_real_t center[3] = {0, 0, 0};
    int a;
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
    fill_position(node, utime, pose);
    ++node->counts.published;
}

/* The track starts again with the next measurement (a gap longer than
 * max_dt, or a new clock): the filter reset, the restart counted, the kept
 * frames forgotten. */
static void restart_track(filter_node_t *node)
{
    hkf_reset(&node->filter);
    (void)hkf_calibration_reset(&node->calibration, &node->filter);
    hkf_position_restart(&node->position);
    ++node->counts.restarts;
    second_model_forget_frames(&node->second);
    second_position_forget_frames(&node->second_position);
}

static int finite_angles(const hkf_head_pose_measurement_t *m)
{
    return isfinite(m->pitch) && isfinite(m->yaw) && isfinite(m->roll) &&
           fabsf(m->pitch) <= HKF_MAX_ABS_ANGLE && fabsf(m->yaw) <= HKF_MAX_ABS_ANGLE &&
           fabsf(m->roll) <= HKF_MAX_ABS_ANGLE;
}

/* The order, duplicate and value rules on m's capture time and angles; when m
 * is taken, *dt is its step from the last one (0 for the first) and a gap
 * longer than max_dt has restarted the track. Returns 0 when m is rejected. */
static int take_time(filter_node_t *node, const hkf_head_pose_measurement_t *m, hkf_real_t *dt)
{
    *dt = 0;
    if (node->have_time && m->utime < node->last_utime) {
        ++node->counts.out_of_order;
        return 0;
    }
    if (node->have_time && m->utime == node->last_utime) {
        ++node->counts.duplicates;
        return 0;
    }
    if (m->valid && !finite_angles(m)) {
        ++node->counts.bad_values;
        return 0;
    }
    if (node->have_time) {
        *dt = (hkf_real_t)(((double)m->utime - (double)node->last_utime) * 1e-6);
    }
    node->have_time = 1;
    node->last_utime = m->utime;
    if (hkf_get_status(&node->filter) != HKF_STATUS_UNINITIALIZED && *dt > node->config->settings.max_dt) {
        restart_track(node); /* a gap longer than max_dt: the track starts again from this measurement */
    }
    return 1;
}

/* A frame without a face: the filter coasts (hkf_predict). */
static int coast(filter_node_t *node, const hkf_head_pose_measurement_t *m, hkf_real_t dt, hkf_head_pose_t *pose)
{
    hkf_output_t out;
    ++node->counts.without_face;
    if (hkf_get_status(&node->filter) == HKF_STATUS_UNINITIALIZED && m->model != NULL &&
        strncmp(m->model, node->model, sizeof node->model) != 0 && setup_filter(node, m->model) == HKF_OK) {
        second_model_forget_frames(&node->second); /* no track yet: the filter is this model's, should a second model start one here */
    }
    second_model_keep_frame(&node->second, m, NULL, dt, &node->filter, &node->calibration);
    take_position(node, m); /* noted: no position */
    if (hkf_predict(&node->filter, dt, &out) != HKF_OK) { /* no track yet (or again, after a gap) */
        return 0;
    }
    (void)hkf_calibration_update(&node->calibration, &node->filter, NULL, dt);
    fill_pose(node, &out, m->utime, pose);
    return 1;
}

/* A measurement: the filter set up for its model (a change of model restarts
 * the track with the new curves), then hkf_update. */
static int update(filter_node_t *node, const hkf_head_pose_measurement_t *m, hkf_real_t dt, hkf_head_pose_t *pose)
{
    const hkf_real_t z[3] = {m->pitch, m->yaw, m->roll};
    hkf_output_t out;
    int known;
    if (strncmp(m->model ? m->model : "", node->model, sizeof node->model) != 0) {
        if (hkf_get_status(&node->filter) != HKF_STATUS_UNINITIALIZED) {
            ++node->counts.restarts;
        }
        if (setup_filter(node, m->model ? m->model : "") != HKF_OK) {
            return 0; /* cannot happen: the config was validated at start */
        }
        second_model_forget_frames(&node->second);
    }
    (void)node_config_for_model(node->config, node->model, &known);
    node->counts.unknown_models += !known;
    second_model_keep_frame(&node->second, m, z, dt, &node->filter, &node->calibration);
    if (hkf_update(&node->filter, z, dt, &out) != HKF_OK) {
        ++node->counts.bad_values;
        second_model_unkeep_newest(&node->second);
        return 0;
    }
    (void)hkf_calibration_update(&node->calibration, &node->filter, z, dt); /* for the next measurement's R */
    node->last_measurement_utime = m->utime;
    take_position(node, m);
    fill_pose(node, &out, m->utime, pose);
    return 1;
}

int filter_node_measurement(filter_node_t *node, const hkf_head_pose_measurement_t *m, hkf_head_pose_t *pose)
{
    hkf_real_t dt;
    ++node->counts.received;
    if (!take_time(node, m, &dt)) {
        return 0;
    }
    return m->valid ? update(node, m, dt, pose) : coast(node, m, dt, pose);
}

/* Capture-clock step minus arrival-clock step, in double: stamps may be anything. */
static double clock_skew_us(int64_t utime, int64_t arrival, int64_t ref_utime, int64_t ref_arrival)
{
    return ((double)utime - (double)ref_utime) - ((double)arrival - (double)ref_arrival);
}

/* One publisher: 1 when m continues the followed estimator's frame counter, or
 * when that one has gone silent (then m's publisher is followed); else 0. */
static int from_followed_publisher(filter_node_t *node, const hkf_head_pose_measurement_t *m, int64_t arrival_utime)
{
    if (node->have_stream) {
        const double step = (double)m->seq - (double)node->stream_seq;
        const int continues = step >= 1 && step <= (double)FILTER_NODE_MAX_SEQ_STEP;
        const int silent =
            (double)arrival_utime - (double)node->stream_arrival_utime > (double)FILTER_NODE_STREAM_TIMEOUT_US;
        if (!continues && !silent) {
            return 0;
        }
    }
    node->have_stream = 1;
    node->stream_seq = m->seq;
    node->stream_arrival_utime = arrival_utime;
    return 1;
}

/* The node follows a new capture clock: the track restarts as after a gap. */
static void resync_clock(filter_node_t *node)
{
    ++node->counts.clock_resyncs;
    node->have_time = 0;
    if (hkf_get_status(&node->filter) != HKF_STATUS_UNINITIALIZED) {
        restart_track(node);
    } else {
        second_model_forget_frames(&node->second);
        second_position_forget_frames(&node->second_position);
    }
}

/* A measurement the node's time reference rejects (clock rule, or older than
 * the last one taken). FILTER_NODE_RESYNC_MESSAGES such in a row that agree
 * with each other - each later than the one before, with a capture step that
 * matches the arrival step - mean the reference is what was wrong: on the last
 * of them the node follows the new clock and returns 1; before, 0. */
static int follows_rejected_stamps(filter_node_t *node, const hkf_head_pose_measurement_t *m, int64_t arrival_utime)
{
    const int consistent =
        node->jump_count > 0 && m->utime > node->jump_utime &&
        fabs(clock_skew_us(m->utime, arrival_utime, node->jump_utime, node->jump_arrival_utime)) <=
            (double)FILTER_NODE_CLOCK_JUMP_US;
    node->jump_count = consistent ? node->jump_count + 1 : 1;
    node->jump_utime = m->utime;
    node->jump_arrival_utime = arrival_utime;
    if (node->jump_count < FILTER_NODE_RESYNC_MESSAGES) {
        return 0;
    }
    resync_clock(node);
    return 1;
}

/* The clock rule: 0 when m's stamp disagrees with its arrival (a corrupt stamp,
 * or the first messages after a clock jump); 1 to go on. */
static int clock_agrees(filter_node_t *node, const hkf_head_pose_measurement_t *m, int64_t arrival_utime)
{
    return !node->have_time ||
           fabs(clock_skew_us(m->utime, arrival_utime, node->last_utime, node->last_arrival_utime)) <=
               (double)FILTER_NODE_CLOCK_JUMP_US ||
           follows_rejected_stamps(node, m, arrival_utime);
}

/* The stale rule: 0 when m is older than the last measurement taken (out of
 * order); 1 to go on. Older ones that agree with each other mean the last one
 * taken was the odd one out: a forged stamp ahead of time, or a clock that
 * stepped back together with the receive clock (which the clock rule cannot
 * see). The node then follows them, so that no single message holds tracking
 * up for longer than a few frames. */
static int not_stale(filter_node_t *node, const hkf_head_pose_measurement_t *m, int64_t arrival_utime)
{
    return !node->have_time || m->utime >= node->last_utime || follows_rejected_stamps(node, m, arrival_utime);
}

/* Fuses m, the second measurement of kept frame `index` (second_model_fuse), and counts it. */
static void fuse_second(filter_node_t *node, int index, const hkf_head_pose_measurement_t *m)
{
    int known;
    if (!second_model_fuse(&node->second, node->config, index, m, &node->filter, &node->calibration)) {
        ++node->counts.unpaired;
        return;
    }
    (void)node_config_for_model(node->config, node->second.frames[index].second_model, &known);
    if (m->utime > node->last_measurement_utime) {
        node->last_measurement_utime = m->utime;
    }
    node->counts.unknown_models += !known;
    ++node->counts.paired;
}

int filter_node_receive(filter_node_t *node, const hkf_head_pose_measurement_t *m, int64_t arrival_utime,
                        hkf_head_pose_t *pose)
{
    const int64_t previous_utime = node->last_utime;
    const int had_time = node->have_time;
    const int second_of = second_model_frame_of(&node->second, m);
    int publish;
    if (second_of >= 0 || (node->have_stream && second_model_too_late(&node->second, m, node->model))) {
        /* a second model's measurement of a frame taken */
        ++node->counts.received;
        if (m->valid && !finite_angles(m)) {
            ++node->counts.bad_values;
        } else if (!m->valid || second_of < 0) {
            ++node->counts.unpaired;
        } else {
            fuse_second(node, second_of, m);
        }
        take_second_position(node, m);
        return 0;
    }
    if (!from_followed_publisher(node, m, arrival_utime)) {
        ++node->counts.received;
        ++node->counts.other_publisher;
        return 0;
    }
    if (!clock_agrees(node, m, arrival_utime)) {
        ++node->counts.received;
        ++node->counts.clock_jumps;
        return 0;
    }
    if (!not_stale(node, m, arrival_utime)) {
        ++node->counts.received;
        ++node->counts.out_of_order;
        return 0;
    }
    second_model_note_frame(&node->second, m->seq, m->utime);
    publish = filter_node_measurement(node, m, pose);
    if (node->have_time && (!had_time || node->last_utime != previous_utime)) {
        /* taken: the new time reference */
        node->last_arrival_utime = arrival_utime;
        node->jump_count = 0;
        node->lost_published = 0; /* the estimator speaks: no silence */
    }
    return publish;
}

int filter_node_extrapolate(filter_node_t *node, int64_t utime, hkf_head_pose_t *pose)
{
    hkf_output_t out;
    const double ahead = ((double)utime - (double)node->last_utime) * 1e-6; /* stamps may be anything */
    if (!node->have_time || ahead < 0.0 || ahead > (double)node->config->settings.coast_time) {
        return 0; /* nothing to extrapolate, or the estimator has gone quiet */
    }
    if (hkf_extrapolate(&node->filter, (hkf_real_t)ahead, &out) != HKF_OK) {
        return 0; /* no track */
    }
    fill_pose(node, &out, utime, pose);
    ++node->counts.extrapolated;
    return 1;
}

/* The silence's length (us) at which the next LOST pose is due: coast_time,
 * then every FILTER_NODE_LOST_REPEAT_US. */
static int64_t next_lost_after_us(const filter_node_t *node)
{
    return (int64_t)ceil(1e6 * (double)node->config->settings.coast_time) +
           node->lost_published * FILTER_NODE_LOST_REPEAT_US;
}

int64_t filter_node_silence_due(const filter_node_t *node)
{
    const int64_t after = next_lost_after_us(node);
    if (!node->have_time || hkf_get_status(&node->filter) == HKF_STATUS_UNINITIALIZED ||
        node->last_arrival_utime > INT64_MAX - after) {
        return 0;
    }
    return node->last_arrival_utime + after;
}

int filter_node_silence(filter_node_t *node, int64_t arrival_utime, hkf_head_pose_t *pose)
{
    hkf_output_t out;
    const int64_t due = filter_node_silence_due(node), after = next_lost_after_us(node);
    if (due == 0 || arrival_utime < due || node->last_utime > INT64_MAX - after ||
        hkf_get_output(&node->filter, &out) != HKF_OK) {
        return 0; /* no track, not silent long enough, or a clock at its end */
    }
    if (node->lost_published == 0) {
        ++node->counts.silences;
    }
    ++node->lost_published;
    out.status = HKF_STATUS_LOST; /* as the filter itself does after coast_time: angle held, rate zero */
    out.rate[0] = out.rate[1] = out.rate[2] = 0;
    out.flags |= HKF_FLAG_EXTRAPOLATED; /* not a posterior */
    /* stamped when it became due on the capture clock, so live and offline agree */
    fill_pose(node, &out, node->last_utime + after, pose);
    return 1;
}

int filter_node_command(filter_node_t *node, const hkf_tracker_command_t *command)
{
    switch (command->command) {
    case HKF_TRACKER_COMMAND_T_RECENTER:
        ++node->counts.commands;
        second_model_forget_frames(&node->second); /* a late second measurement would redo frames on the old centre */
        (void)hkf_recenter(&node->filter); /* without a track there is nothing to centre on */
        /* on the position last published (the angles' frame time): held or coasting, it reads 0 */
        (void)hkf_position_recenter_at(&node->position, (hkf_real_t)position_ahead(node, node->last_utime));
        return 0;
    case HKF_TRACKER_COMMAND_T_RESET:
        ++node->counts.commands;
        second_model_forget_frames(&node->second);
        second_position_init(&node->second_position); /* the models' offset too: nothing of before stays */
        hkf_position_reset(&node->position);
        (void)setup_filter(node, node->model);
        return 0;
    default:
        return -1;
    }
}
