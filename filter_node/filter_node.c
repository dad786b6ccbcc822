/* filter_node.c - see filter_node.h. */
#include "filter_node.h"

#include <math.h>
#include <string.h>

#include "node_await.h"
#include "node_pose.h"

/* The filter set up for the model `model` (its settings: resolved), the calibration beside it. */
static int setup_filter(filter_node_t *node, const char *model, const resolved_model_t *resolved)
{
    if (strncmp(model, node->model, sizeof node->model) != 0) {
        second_model_forget_alignment(&node->second); /* first minus second: another first model, another curve */
    }
    if (model != node->model) {
        strncpy(node->model, model, sizeof node->model - 1);
        node->model[sizeof node->model - 1] = '\0';
    }
    int result = hkf_init(&node->filter, &resolved->settings);
    result = result != HKF_OK ? result : hkf_calibration_init(&node->calibration, &node->config->calibration, &node->filter);
    node_rest_keep(&node->rest, &node->filter); /* a rest measured is this camera's and player's, whatever the model */
    return result;
}

int filter_node_init(filter_node_t *node, const node_config_t *config)
{
    int result;
    memset(node, 0, sizeof *node);
    node->config = config;
    node->published_utime = INT64_MIN;
    stream_admission_init(&node->admission);
    second_model_init(&node->second);
    result = node_position_init(&node->position, &config->position, &config->position_calibration);
    if (result == HKF_OK) {
        result = node_rest_init(&node->rest, &config->rest); /* tracking starts: a rest is asked for */
    }
    if (result == HKF_OK) {
        result = resolved_models_init(&node->models, config);
    }
    if (result != HKF_OK) {
        return result; /* cannot happen: the config was checked */
    }
    return setup_filter(node, "", resolved_models_find(&node->models, ""));
}

/* What a measurement's position became, counted. */
static void count_position(filter_node_t *node, node_position_result_t result)
{
    node->counts.bad_positions += result == NODE_POSITION_BAD;
    node->counts.positions_gated += result == NODE_POSITION_GATED;
}

/* The first model's frame m (its model: model): its position into the position filter (node_position.h),
 * with the model's position R scale. */
static void take_position(filter_node_t *node, const hkf_head_pose_measurement_t *m, const resolved_model_t *model)
{
    count_position(node, node_position_take_first(&node->position, m, model->position_r_scale));
}

/* A second model's measurement m of kept frame `frame` (NULL: no longer kept): its position stands in
 * where the first model measured none. */
static void take_second_position(filter_node_t *node, const hkf_head_pose_measurement_t *m,
                                 const second_model_frame_t *frame, const resolved_model_t *model)
{
    count_position(node, node_position_take_second(&node->position, m, frame, model->position_r_scale));
}

/* The track starts again with the next measurement (a gap longer than
 * max_dt, or a new clock): the filter reset, the restart counted, the kept
 * frames forgotten. */
static void restart_track(filter_node_t *node)
{
    node_await_settle_all(node); /* one pose per frame: a waiting frame's is published before its step is forgotten */
    hkf_reset(&node->filter);
    (void)hkf_calibration_reset(&node->calibration, &node->filter);
    node_position_restart(&node->position);
    ++node->counts.restarts;
    second_model_forget_frames(&node->second);
}

static int finite_angles(const hkf_head_pose_measurement_t *m)
{
    return isfinite(m->pitch) && isfinite(m->yaw) && isfinite(m->roll) &&
           fabsf(m->pitch) <= HKF_MAX_ABS_ANGLE && fabsf(m->yaw) <= HKF_MAX_ABS_ANGLE &&
           fabsf(m->roll) <= HKF_MAX_ABS_ANGLE;
}

/* What admission made of m after its publisher, clock and stale rules (stream_admission.h): the order
 * and value rules' refusals counted; when m is taken, *dt is its step from the last one (0 for the first)
 * and a gap longer than max_dt has restarted the track. Returns 0 when m is refused. */
static int taken(filter_node_t *node, const stream_admission_result_t *r, hkf_real_t *dt)
{
    *dt = 0;
    switch (r->order) {
    case STREAM_OUT_OF_ORDER:
        ++node->counts.out_of_order;
        return 0;
    case STREAM_DUPLICATE:
        ++node->counts.duplicates;
        return 0;
    case STREAM_IN_ORDER:
        break;
    }
    if (!r->taken) {
        ++node->counts.bad_values;
        return 0;
    }
    *dt = (hkf_real_t)r->dt;
    if (hkf_get_status(&node->filter) != HKF_STATUS_UNINITIALIZED && *dt > node->config->settings.max_dt) {
        restart_track(node); /* a gap longer than max_dt: the track starts again from this measurement */
    }
    return 1;
}

/* The angles' values admission asks about: finite and in range, or none (no face). */
static int values_ok(const hkf_head_pose_measurement_t *m)
{
    return !m->valid || finite_angles(m);
}

/* What the angles made of a first model's measurement (update, coast). */
typedef enum {
    ANGLES_REFUSED, /* its step failed: nothing of it is taken */
    ANGLES_NO_POSE, /* taken, no track to pose yet, or its pose awaits the second model's answer */
    ANGLES_POSE     /* taken: *out is the pose's */
} angles_step_t;

/* How recent a frame with a second model's measurement must be for the next to wait for the second's, and
 * the longest wait: FILTER_NODE_PROMPT_SHARE of coast_time, so that waiting never coasts the track to LOST. */
static int64_t prompt_us(const filter_node_t *node)
{
    return (int64_t)(FILTER_NODE_PROMPT_SHARE * 1e6 * (double)node->config->settings.coast_time);
}

/* One frame's measurement z (NULL: none) to the rest, with the time of the frames not given to it before. */
static void feed_rest(filter_node_t *node, const hkf_real_t *z, hkf_real_t dt)
{
    node_rest_take(&node->rest, &node->filter, z, node->rest_dt + dt);
    node->rest_dt = 0;
}

/* 1 when a frame without the first model's pose waits for the second's: the track is predicted at a turn
 * where the frame would take the second's alone (second_model_awaits on the prediction), and the second
 * answers promptly. There the first model is weak or set aside (hkf-estimator does not run it where the
 * second's newest answer reads a large turn, --second-alone-from-yaw): a pose predicted now would be
 * corrected a frame later, so the frame's pose is the second's step, as for a first reading set aside. */
static int coast_awaits(const filter_node_t *node, hkf_real_t dt, int64_t utime)
{
    hkf_real_t predicted[3];
    return second_model_prediction(&node->filter, dt, predicted) &&
           second_model_awaits(&node->second, &node->models, predicted, &node->filter, dt, utime, prompt_us(node));
}

/* A frame without a face: the filter coasts (hkf_predict), now or, where the second model is awaited
 * (coast_awaits), when its answer comes or at the frame's deadline. */
static angles_step_t coast(filter_node_t *node, const hkf_head_pose_measurement_t *m, const resolved_model_t *model,
                           int64_t arrival, hkf_real_t dt, hkf_output_t *out)
{
    ++node->counts.without_face;
    if (hkf_get_status(&node->filter) == HKF_STATUS_UNINITIALIZED && m->model != NULL &&
        strncmp(m->model, node->model, sizeof node->model) != 0 && setup_filter(node, m->model, model) == HKF_OK) {
        second_model_forget_frames(&node->second); /* no track yet: the filter is this model's, should a second model start one here */
    }
    const int awaits = coast_awaits(node, dt, m->utime);
    const second_model_step_t step = {NULL, dt, awaits, arrival, prompt_us(node)};
    if (!awaits) {
        node_await_settle_all(node); /* its prediction goes out now: the frames still waiting before it go first */
    }
    second_model_keep_frame(&node->second, m, &step, &node->filter, &node->calibration);
    if (hkf_predict(&node->filter, dt, out) != HKF_OK) { /* no track yet (or again, after a gap) */
        return ANGLES_NO_POSE;
    }
    (void)hkf_calibration_update(&node->calibration, &node->filter, NULL, dt);
    node->counts.awaited += awaits;
    if (second_model_answers(&node->second, m->utime, prompt_us(node))) {
        node->rest_dt += dt; /* the second model may see the face: its measurement goes to the rest (take_second) */
    } else {
        node_rest_take(&node->rest, &node->filter, NULL, dt);
        node->rest_dt = 0;
    }
    return awaits ? ANGLES_NO_POSE : ANGLES_POSE; /* waiting: its pose when the answer comes (take_second) */
}

/* A measurement: the filter set up for its model (a change of model restarts
 * the track with the new curves), then hkf_update. */
static angles_step_t update(filter_node_t *node, const hkf_head_pose_measurement_t *m, const resolved_model_t *model,
                            int64_t arrival, hkf_real_t dt, hkf_output_t *out)
{
    const hkf_real_t z[3] = {m->pitch, m->yaw, m->roll};
    hkf_filter_t before;
    hkf_calibration_t calibration_before;
    if (strncmp(m->model ? m->model : "", node->model, sizeof node->model) != 0) {
        if (hkf_get_status(&node->filter) != HKF_STATUS_UNINITIALIZED) {
            ++node->counts.restarts;
        }
        if (setup_filter(node, m->model ? m->model : "", model) != HKF_OK) {
            return ANGLES_REFUSED; /* cannot happen: the config was validated at start */
        }
        second_model_forget_frames(&node->second);
    }
    node->counts.unknown_models += !model->in_table;
    const int awaits = second_model_awaits(&node->second, &node->models, z, &node->filter, dt, m->utime, prompt_us(node));
    if (!awaits) {
        node_await_settle_all(node); /* its pose goes out now: the frames still waiting before it go first */
    }
    before = node->filter;
    calibration_before = node->calibration;
    if (awaits && hkf_predict(&node->filter, dt, out) == HKF_OK) {
        ++node->counts.awaited; /* its step and its pose when the second model's measurement comes (take_second) */
        (void)hkf_calibration_update(&node->calibration, &node->filter, NULL, dt);
        const second_model_step_t waiting = {z, dt, 1, arrival, prompt_us(node)};
        second_model_keep_frame(&node->second, m, &waiting, &before, &calibration_before);
        feed_rest(node, z, dt); /* the head measured at any yaw: a rest beside the screen too */
        node->last_measurement_utime = m->utime;
        return ANGLES_NO_POSE;
    }
    if (hkf_update(&node->filter, z, dt, out) != HKF_OK) {
        ++node->counts.bad_values;
        return ANGLES_REFUSED; /* not kept: the step never happened */
    }
    (void)hkf_calibration_update(&node->calibration, &node->filter, z, dt); /* for the next measurement's R */
    const second_model_step_t step = {z, dt, 0, arrival, prompt_us(node)};
    second_model_keep_frame(&node->second, m, &step, &before, &calibration_before);
    feed_rest(node, z, dt); /* after the frame is kept: a redo keeps the rest (fuse_second) */
    node->last_measurement_utime = m->utime;
    return ANGLES_POSE;
}

/* A measurement taken, its step dt: the angles (a frame with a face updates them, one without coasts),
 * the position, the pose. Returns 1 when *pose is to be published. */
static int measure(filter_node_t *node, const hkf_head_pose_measurement_t *m, int64_t arrival, hkf_real_t dt,
                   hkf_head_pose_t *pose)
{
    const resolved_model_t *model = resolved_models_find(&node->models, m->model); /* resolved at start */
    hkf_output_t out;
    const angles_step_t angles =
        m->valid ? update(node, m, model, arrival, dt, &out) : coast(node, m, model, arrival, dt, &out);
    if (angles == ANGLES_REFUSED) {
        return 0;
    }
    take_position(node, m, model);
    if (angles == ANGLES_NO_POSE) {
        return 0;
    }
    node_pose_fill(node, &out, m->utime, pose);
    return 1;
}

int filter_node_measurement(filter_node_t *node, const hkf_head_pose_measurement_t *m, hkf_head_pose_t *pose)
{
    hkf_real_t dt;
    const stream_admission_result_t r = stream_admission_admit_time(&node->admission, m->utime, values_ok(m));
    ++node->counts.received;
    return taken(node, &r, &dt) && measure(node, m, m->utime, dt, pose);
}

/* The node follows a new capture clock (stream_admission.h): the track restarts as after a gap. The
 * position restarts too when only it had started (a second model's position in a frame whose angles
 * were not taken): its last stamp is on the old clock, and it would refuse every later one. */
static void resync_clock(filter_node_t *node)
{
    ++node->counts.clock_resyncs;
    node->published_utime = INT64_MIN; /* poses on the new clock follow their own */
    if (hkf_get_status(&node->filter) != HKF_STATUS_UNINITIALIZED) {
        restart_track(node);
    } else {
        node_await_settle_all(node);
        node_position_restart(&node->position);
        second_model_forget_frames(&node->second);
    }
}

/* What admission made of m by its publisher, clock and stale rules (stream_admission.h): 1 when they
 * passed (on a new clock the track restarts), 0 when m was refused (counted). */
static int passed(filter_node_t *node, stream_verdict_t verdict)
{
    switch (verdict) {
    case STREAM_GO_ON:
        return 1;
    case STREAM_NEW_CLOCK:
        resync_clock(node);
        return 1;
    case STREAM_OTHER_PUBLISHER:
        ++node->counts.other_publisher;
        break;
    case STREAM_CLOCK_JUMP:
        ++node->counts.clock_jumps;
        break;
    case STREAM_STALE:
        ++node->counts.out_of_order;
        break;
    case STREAM_SECOND_MODEL: /* taken apart before (take_second) */
        break;
    }
    return 0;
}

/* A second model's measurement m: fused into its kept frame when its angles are good (*frame: that
 * frame, NULL when no longer kept; *posterior: the output of its step), and counted. Returns 1 when fused. */
static int fuse_second(filter_node_t *node, const hkf_head_pose_measurement_t *m, const resolved_model_t *model,
                       int64_t arrival, const second_model_frame_t **frame, hkf_output_t *posterior)
{
    const int bad = m->valid && !finite_angles(m);
    second_model_track_t track;
    track.filter = m->valid && !bad ? &node->filter : NULL;
    track.calibration = &node->calibration;
    if (!second_model_take(&node->second, &node->models, m, arrival, &track, frame)) {
        ++*(bad ? &node->counts.bad_values : &node->counts.unpaired);
        return 0;
    }
    node_rest_keep(&node->rest, &node->filter); /* the frames redone from before the player's rest or RECENTER */
    if (*frame == &node->second.frames[node->second.frame_newest] && !(*frame)->valid && node->rest_dt > 0) {
        feed_rest(node, (*frame)->z2, 0); /* a face only the second model sees: its measurement, aligned */
    }

    if (m->utime > node->last_measurement_utime) {
        node->last_measurement_utime = m->utime;
    }
    node->counts.unknown_models += !model->in_table;
    ++node->counts.paired;
    node->counts.gross_refused += (*frame)->gross != SECOND_MODEL_GROSS_NONE;
    *posterior = track.posterior;
    return 1;
}

/* The pose once a second measurement is fused into `frame`, published only where the frame's pose has not
 * gone out, so that the second model's measurement reaches the game now:
 * - the frame's first measurement waited for it (second_model_awaits): the frame's own posterior, at its
 *   time, unless a later pose is out already. A frame or more late (a slow second model) it is not
 *   predicted on to the newest frame, whose first measurement waits too: at the end of a fast turn that
 *   prediction would overshoot the stop and step back;
 * - the first model found no face and the frame is the newest (its pose was a prediction): the posterior.
 * Elsewhere the frame's pose is out already, and the correction is folded into the next frame's: one pose
 * per measured frame, never a second one that steps back. 0 while there is no track. */
static int pose_after_fusing(filter_node_t *node, const second_model_frame_t *frame, const hkf_output_t *posterior,
                             hkf_head_pose_t *pose)
{
    hkf_output_t out;
    if (frame->awaited) {
        if (frame->utime <= node->published_utime) {
            return 0;
        }
        node_pose_fill(node, posterior, frame->utime, pose);
        pose->measurement_utime = frame->utime;
        return 1;
    }
    if (frame != &node->second.frames[node->second.frame_newest] || frame->valid ||
        hkf_get_status(&node->filter) == HKF_STATUS_UNINITIALIZED || hkf_get_output(&node->filter, &out) != HKF_OK) {
        return 0;
    }
    node_pose_fill(node, &out, node->admission.last_utime, pose);
    return 1;
}

/* A second model's measurement m of one of the followed publisher's frames: its angles fused into that
 * frame while it is kept (a frame no longer kept: too late), its position standing in where the first
 * model measured none, the pose. Returns 1 when *pose is to be published (pose_after_fusing). */
static int take_second(filter_node_t *node, const hkf_head_pose_measurement_t *m, int64_t arrival,
                       hkf_head_pose_t *pose)
{
    const resolved_model_t *model = resolved_models_find(&node->models, m->model); /* resolved at start */
    const second_model_frame_t *frame;
    hkf_output_t posterior;
    node_await_settle(node, INT64_MIN, m->utime); /* one pose per frame, in order: the frames waiting before this one first */
    const int fused = fuse_second(node, m, model, arrival, &frame, &posterior);
    take_second_position(node, m, frame, model);
    if (fused && pose_after_fusing(node, frame, &posterior, pose)) {
        node_await_queue(node, pose);
    }
    return node_await_unqueue(node, pose);
}

int filter_node_receive(filter_node_t *node, const hkf_head_pose_measurement_t *m, int64_t arrival_utime,
                        hkf_head_pose_t *pose)
{
    const stream_measurement_t described = {
        m->seq, m->utime, arrival_utime, strncmp(m->model ? m->model : "", node->model, sizeof node->model) != 0,
        values_ok(m)};
    const stream_admission_result_t r = stream_admission_admit(&node->admission, &described);
    hkf_real_t dt;
    ++node->counts.received; /* every measurement that reaches the node, whatever becomes of it */
    if (r.verdict == STREAM_SECOND_MODEL) {
        return take_second(node, m, arrival_utime, pose);
    }
    if (!passed(node, r.verdict) || !taken(node, &r, &dt)) {
        return 0;
    }
    node->lost_published = 0; /* the estimator speaks: no silence */
    node_await_settle(node, arrival_utime, INT64_MIN); /* waiting frames whose deadline passed before this one came go first */
    if (measure(node, m, arrival_utime, dt, pose)) {
        node_await_queue(node, pose);
    }
    return node_await_unqueue(node, pose);
}

int filter_node_extrapolate(filter_node_t *node, int64_t utime, hkf_head_pose_t *pose)
{
    hkf_output_t out;
    const stream_admission_t *a = &node->admission;
    const double ahead = ((double)utime - (double)a->last_utime) * 1e-6; /* stamps may be anything */
    if (!a->have_time || ahead < 0.0 || ahead > (double)node->config->settings.coast_time) {
        return 0; /* nothing to extrapolate, or the estimator has gone quiet */
    }
    if (hkf_extrapolate(&node->filter, (hkf_real_t)ahead, &out) != HKF_OK) {
        return 0; /* no track */
    }
    node_pose_fill(node, &out, utime, pose);
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
    const stream_admission_t *a = &node->admission;
    if (!a->have_time || hkf_get_status(&node->filter) == HKF_STATUS_UNINITIALIZED ||
        a->last_arrival_utime > INT64_MAX - after || a->last_utime > INT64_MAX - after) {
        return 0; /* no track, or a clock at its end: no LOST pose could be stamped (and none is due) */
    }
    return a->last_arrival_utime + after;
}

int filter_node_silence(filter_node_t *node, int64_t arrival_utime, hkf_head_pose_t *pose)
{
    hkf_output_t out;
    const int64_t due = filter_node_silence_due(node), after = next_lost_after_us(node);
    if (due == 0 || arrival_utime < due || node->admission.last_utime > INT64_MAX - after ||
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
    /* stamped when it became due on the capture clock, so live and offline agree; a nominal stamp, so no
     * reference for later poses: a frame captured before it that arrives after it (an estimator stalled
     * beyond the coast time) keeps its own stamp rather than be extrapolated up to coast_time */
    {
        const int64_t reference = node->published_utime;
        node_pose_fill(node, &out, node->admission.last_utime + after, pose);
        node->published_utime = reference;
    }
    return 1;
}

void filter_node_status(const filter_node_t *node, const hkf_head_pose_t *pose, hkf_tracker_status_t *status)
{
    node_rest_status(&node->rest, &node->filter, pose->utime, pose->seq, status);
    status->commands = (int32_t)node->counts.commands;
    status->settings_saved = (int32_t)node->counts.settings_saved;
    status->settings_unsaved = (int32_t)node->counts.settings_unsaved;
}

int filter_node_command(filter_node_t *node, const hkf_tracker_command_t *command)
{
    switch (command->command) {
    case HKF_TRACKER_COMMAND_T_RECENTER:
        ++node->counts.commands;
        node_await_settle_all(node); /* the waiting frames' poses (queued) on the centre they were measured with */
        second_model_forget_frames(&node->second); /* a late second measurement would redo frames on the old centre */
        (void)hkf_recenter(&node->filter); /* without a track there is nothing to centre on */
        node_rest_recentered(&node->rest, &node->filter); /* the player's centre; the rest's mean once it is measured */
        node->rest_dt = 0;
        /* the position's centre: the position last published (at the angles' frame time), so that it reads 0 after */
        node_position_recenter(&node->position, node->admission.last_utime);
        return 0;
    case HKF_TRACKER_COMMAND_T_RESET:
        ++node->counts.commands;
        node_await_settle_all(node);
        second_model_forget_frames(&node->second);
        second_model_forget_alignment(&node->second); /* a curve learnt from a broken model does not outlive it */
        node_position_reset(&node->position); /* the models' offset too: nothing of before stays */
        node_rest_forget(&node->rest); /* before the set-up, which would keep it */
        node->rest_dt = 0;
        (void)setup_filter(node, node->model, resolved_models_find(&node->models, node->model));
        return 0;
    default:
        return -1;
    }
}
