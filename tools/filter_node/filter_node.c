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
    return hkf_init(&node->filter, &s);
}

/* The wire layout: hash, utime, seq (8 bytes each), the model string as a
 * big-endian int32 length with its NUL and the bytes, then valid (1),
 * pitch, yaw, roll (4 each), face_box (16), detection_score (4), inference_us (8). */
enum { MODEL_AT = 24, TAIL = 1 + 12 + 16 + 4 + 8 };

/* The model string's claimed length (with its NUL); the payload has at least MODEL_AT + 4 bytes. */
static long model_length(const unsigned char *bytes)
{
    return ((long)bytes[MODEL_AT] << 24) | ((long)bytes[MODEL_AT + 1] << 16) | ((long)bytes[MODEL_AT + 2] << 8) |
           bytes[MODEL_AT + 3];
}

int filter_node_decode(const void *data, int size, hkf_head_pose_measurement_t *m)
{
    const unsigned char *bytes = data;
    long length;
    if (data == NULL || size < MODEL_AT + 4 + 1 + TAIL) {
        return -1;
    }
    length = model_length(bytes);
    if (length < 1 || length > NODE_MODEL_NAME_MAX || MODEL_AT + 4 + length + TAIL != size ||
        bytes[MODEL_AT + 4 + length - 1] != '\0') {
        return -1;
    }
    memset(m, 0, sizeof *m); /* so that a cleanup after a failed decode frees nothing it did not allocate */
    if (hkf_head_pose_measurement_t_decode(data, 0, size, m) != size) { /* e.g. another type's hash */
        hkf_head_pose_measurement_t_decode_cleanup(m);
        return -1;
    }
    return 0;
}

int filter_node_model_id_too_long(const void *data, int size)
{
    long length;
    if (data == NULL || size < MODEL_AT + 4) {
        return 0;
    }
    length = model_length(data);
    return length > NODE_MODEL_NAME_MAX && length <= size - (MODEL_AT + 4);
}

int filter_node_init(filter_node_t *node, const node_config_t *config)
{
    memset(node, 0, sizeof *node);
    node->config = config;
    node->align_frames = FILTER_NODE_ALIGN_FRAMES;
    return setup_filter(node, "");
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
    ++node->counts.published;
}

/* The kept frames (for a late second measurement): forgotten on a restart. */
static void forget_frames(filter_node_t *node)
{
    node->frame_count = 0;
}

/* Keeps this frame's step, about to be made on node->filter: z (NULL: no face), dt. */
static void keep_frame(filter_node_t *node, const hkf_head_pose_measurement_t *m, const hkf_real_t z[3], hkf_real_t dt)
{
    filter_node_frame_t *frame;
    node->frame_newest = (node->frame_newest + 1) % FILTER_NODE_PAIR_FRAMES;
    if (node->frame_count < FILTER_NODE_PAIR_FRAMES) {
        ++node->frame_count;
    }
    frame = &node->frames[node->frame_newest];
    memset(frame, 0, sizeof *frame);
    frame->seq = m->seq;
    frame->utime = m->utime;
    strncpy(frame->model, m->model ? m->model : "", sizeof frame->model - 1);
    frame->valid = z != NULL;
    if (z != NULL) {
        memcpy(frame->z, z, sizeof frame->z);
    }
    frame->dt = dt;
    frame->before = node->filter;
}

/* The track starts again with the next measurement (a gap longer than
 * max_dt, or a new clock): the filter reset, the restart counted, the kept
 * frames forgotten. */
static void restart_track(filter_node_t *node)
{
    hkf_reset(&node->filter);
    ++node->counts.restarts;
    forget_frames(node);
}

/* The newest kept frame's step failed: it never happened. */
static void unkeep_newest(filter_node_t *node)
{
    if (node->frame_count > 0) {
        --node->frame_count;
        node->frame_newest = (node->frame_newest + FILTER_NODE_PAIR_FRAMES - 1) % FILTER_NODE_PAIR_FRAMES;
    }
}

static int finite_angles(const hkf_head_pose_measurement_t *m)
{
    return isfinite(m->pitch) && isfinite(m->yaw) && isfinite(m->roll) &&
           fabsf(m->pitch) <= HKF_MAX_ABS_ANGLE && fabsf(m->yaw) <= HKF_MAX_ABS_ANGLE &&
           fabsf(m->roll) <= HKF_MAX_ABS_ANGLE;
}

int filter_node_measurement(filter_node_t *node, const hkf_head_pose_measurement_t *m, hkf_head_pose_t *pose)
{
    hkf_output_t out;
    hkf_real_t dt = 0;
    int result;
    ++node->counts.received;
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
        dt = (hkf_real_t)(((double)m->utime - (double)node->last_utime) * 1e-6);
    }
    node->have_time = 1;
    node->last_utime = m->utime;
    if (node->filter.status != HKF_STATUS_UNINITIALIZED && dt > node->config->settings.max_dt) {
        restart_track(node); /* a gap longer than max_dt: the track starts again from this measurement */
    }

    if (!m->valid) {
        ++node->counts.without_face;
        if (node->filter.status == HKF_STATUS_UNINITIALIZED && m->model != NULL &&
            strncmp(m->model, node->model, sizeof node->model) != 0 && setup_filter(node, m->model) == HKF_OK) {
            forget_frames(node); /* no track yet: the filter is this model's, should a second model start one here */
        }
        keep_frame(node, m, NULL, dt);
        result = hkf_predict(&node->filter, dt, &out);
        if (result != HKF_OK) { /* no track yet (or again, after a gap) */
            return 0;
        }
        fill_pose(node, &out, m->utime, pose);
        return 1;
    }

    if (strncmp(m->model ? m->model : "", node->model, sizeof node->model) != 0) {
        if (node->filter.status != HKF_STATUS_UNINITIALIZED) {
            ++node->counts.restarts;
        }
        if (setup_filter(node, m->model ? m->model : "") != HKF_OK) {
            return 0; /* cannot happen: the config was validated at start */
        }
        forget_frames(node);
    }
    {
        int known;
        (void)node_config_for_model(node->config, node->model, &known);
        node->counts.unknown_models += !known;
    }
    {
        const hkf_real_t z[3] = {m->pitch, m->yaw, m->roll};
        keep_frame(node, m, z, dt);
        result = hkf_update(&node->filter, z, dt, &out);
    }
    if (result != HKF_OK) {
        ++node->counts.bad_values;
        unkeep_newest(node);
        return 0;
    }
    node->last_measurement_utime = m->utime;
    fill_pose(node, &out, m->utime, pose);
    return 1;
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
    if (node->filter.status != HKF_STATUS_UNINITIALIZED) {
        restart_track(node);
    } else {
        forget_frames(node);
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

/* Two models on one channel: the index of the kept frame m is the second
 * measurement of (same seq and utime, another model), or -1. */
static int frame_of_second(const filter_node_t *node, const hkf_head_pose_measurement_t *m)
{
    int i;
    for (i = 0; i < node->frame_count; ++i) {
        const int index = (node->frame_newest + FILTER_NODE_PAIR_FRAMES - i) % FILTER_NODE_PAIR_FRAMES;
        const filter_node_frame_t *frame = &node->frames[index];
        if (frame->seq == m->seq && frame->utime == m->utime) {
            return strncmp(frame->model, m->model ? m->model : "", sizeof frame->model) != 0 ? index : -1;
        }
    }
    return -1;
}

static int frame_id_slot(int64_t seq)
{
    return (int)((uint64_t)seq % FILTER_NODE_FRAME_IDS);
}

/* A second model's measurement of a frame already passed, too old for the kept
 * frames: its seq and utime are those of one of the followed publisher's last
 * frames, its model another. (Another publisher's seq and utime are not.) */
static int late_second(const filter_node_t *node, const hkf_head_pose_measurement_t *m)
{
    const int slot = frame_id_slot(m->seq);
    return node->have_stream && node->frame_ids[slot].seq == m->seq && node->frame_ids[slot].utime == m->utime &&
           m->utime != 0 && strncmp(node->model, m->model ? m->model : "", sizeof node->model) != 0;
}

/* Where the first model measures a large turn, the second's measurement is taken alone. */
static int first_set_aside(const filter_node_t *node, const filter_node_frame_t *frame)
{
    return frame->valid && fabs((double)frame->z[HKF_AXIS_YAW]) >= (double)node->config->second_alone_from_yaw;
}

/* One kept frame's step on f, as the node made it, with the frame's second
 * measurement if it has one. */
static int redo_step(const filter_node_t *node, hkf_filter_t *f, const filter_node_frame_t *frame)
{
    int result;
    if (frame->paired) {
        int known;
        const hkf_settings_t second = node_config_for_model(node->config, frame->second_model, &known);
        const int first = frame->valid && !first_set_aside(node, frame);
        return hkf_update_pair(f, first ? frame->z : NULL, frame->z2, &second, frame->dt, NULL);
    }
    if (frame->valid) {
        return hkf_update(f, frame->z, frame->dt, NULL);
    }
    result = hkf_predict(f, frame->dt, NULL);
    return result == HKF_ERROR_NOT_INITIALIZED ? HKF_OK : result; /* no track yet, as the node found */
}

/* deg in [-180, 180) */
static double wrap180(double angle)
{
    return angle - 360.0 * floor((angle + 180.0) / 360.0);
}

/* The frame's second measurement (frame->z2) moved onto the first model's
 * frame: plus the running mean of (first - second) over the frames both
 * measured, updated with this frame's difference when the first measured it too. */
static void align_second(filter_node_t *node, filter_node_frame_t *frame)
{
    int a;
    if (strncmp(node->second_model, frame->second_model, sizeof node->second_model) != 0) {
        /* another second model: start over */
        strncpy(node->second_model, frame->second_model, sizeof node->second_model - 1);
        node->second_offset_frames = 0;
        memset(node->second_offset, 0, sizeof node->second_offset);
    }
    /* learnt only where the first model is trusted (where the two are fused): at a large turn the
     * mesh's own error is what the second model is there to avoid */
    if (frame->valid && node->align_frames > 0 && !first_set_aside(node, frame)) {
        const long n = node->second_offset_frames < node->align_frames ? node->second_offset_frames + 1
                                                                       : node->align_frames;
        for (a = 0; a < 3; ++a) {
            double difference = (double)frame->z[a] - (double)frame->z2[a];
            if (a == HKF_AXIS_YAW) {
                difference = wrap180(difference);
            }
            node->second_offset[a] += (hkf_real_t)((difference - (double)node->second_offset[a]) / (double)n);
        }
        node->second_offset_frames = n;
    }
    for (a = 0; a < 3; ++a) {
        double v = (double)frame->z2[a] + (double)node->second_offset[a];
        if (a == HKF_AXIS_YAW) {
            v = wrap180(v);
        }
        frame->z2[a] =
            (hkf_real_t)(v < HKF_MAX_ABS_ANGLE ? (v > -HKF_MAX_ABS_ANGLE ? v : -HKF_MAX_ABS_ANGLE) : HKF_MAX_ABS_ANGLE);
    }
}

/* Fuses m, the second measurement of kept frame `index`: that frame's step
 * again with both (hkf_update_pair), then the steps of the frames after it. */
static void fuse_second(filter_node_t *node, int index, const hkf_head_pose_measurement_t *m)
{
    hkf_filter_t f, before[FILTER_NODE_PAIR_FRAMES];
    filter_node_frame_t *frame = &node->frames[index];
    const int count = (node->frame_newest - index + FILTER_NODE_PAIR_FRAMES) % FILTER_NODE_PAIR_FRAMES + 1;
    int i, known;
    if (frame->paired) { /* one second measurement per frame */
        ++node->counts.unpaired;
        return;
    }
    frame->paired = 1;
    strncpy(frame->second_model, m->model ? m->model : "", sizeof frame->second_model - 1);
    frame->z2[0] = m->pitch;
    frame->z2[1] = m->yaw;
    frame->z2[2] = m->roll;
    align_second(node, frame);
    f = frame->before;
    for (i = 0; i < count; ++i) {
        before[i] = f;
        if (redo_step(node, &f, &node->frames[(index + i) % FILTER_NODE_PAIR_FRAMES]) != HKF_OK) {
            frame->paired = 0; /* cannot happen (the steps were made before, z2 is checked): nothing changes */
            ++node->counts.unpaired;
            return;
        }
    }
    for (i = 1; i < count; ++i) {
        node->frames[(index + i) % FILTER_NODE_PAIR_FRAMES].before = before[i];
    }
    node->filter = f;
    if (m->utime > node->last_measurement_utime) {
        node->last_measurement_utime = m->utime;
    }
    (void)node_config_for_model(node->config, frame->second_model, &known);
    node->counts.unknown_models += !known;
    ++node->counts.paired;
}

int filter_node_receive(filter_node_t *node, const hkf_head_pose_measurement_t *m, int64_t arrival_utime,
                        hkf_head_pose_t *pose)
{
    const int64_t previous_utime = node->last_utime;
    const int had_time = node->have_time;
    const int second_of = frame_of_second(node, m);
    int publish;
    if (second_of >= 0 || late_second(node, m)) { /* a second model's measurement of a frame taken */
        ++node->counts.received;
        if (m->valid && !finite_angles(m)) {
            ++node->counts.bad_values;
        } else if (!m->valid || second_of < 0) {
            ++node->counts.unpaired;
        } else {
            fuse_second(node, second_of, m);
        }
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
    {
        const int slot = frame_id_slot(m->seq);
        node->frame_ids[slot].seq = m->seq;
        node->frame_ids[slot].utime = m->utime;
    }
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
    if (!node->have_time || node->filter.status == HKF_STATUS_UNINITIALIZED ||
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
        forget_frames(node); /* a late second measurement would redo frames on the old centre */
        (void)hkf_recenter(&node->filter); /* without a track there is nothing to centre on */
        return 0;
    case HKF_TRACKER_COMMAND_T_RESET:
        ++node->counts.commands;
        forget_frames(node);
        (void)setup_filter(node, node->model);
        return 0;
    default:
        return -1;
    }
}
