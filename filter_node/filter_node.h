/*
 * filter_node.h - hkf-filter's logic, free of any transport: a raw head pose
 * message in, a filtered one out. The live node and the offline log mode
 * both call these, so they share one code path.
 *
 * Rules:
 * - valid measurement -> hkf_update, publish a pose;
 * - valid = false -> hkf_predict (coast), publish a pose once a track exists;
 * - utime older than the last one -> rejected (out of order); equal -> rejected (duplicate);
 * - non-finite or absurd angles -> rejected and counted, never published;
 * - a gap longer than max_dt -> the track restarts from this measurement;
 * - admission (filter_node_receive): the publisher, clock and stale rules of stream_admission.h
 *   come first; what they refuse is counted (other_publisher, clock_jumps, out_of_order). When the
 *   capture clock really moved, the track restarts on the new clock, as after a gap;
 * - silence (filter_node_silence, live only): an estimator that stops sending
 *   is reported as LOST after coast_time, so a simulator never shows a frozen
 *   pose as if it were tracked;
 * - the measurement's `model` picks its noise curves from the model table;
 *   a change of model restarts the track with the new curves;
 * - two models on one channel (filter_node_receive): a measurement with the
 *   seq and utime of a frame already taken but another model is that frame's
 *   *second* measurement (an estimator running a second model, e.g. WHENet
 *   beside the face mesh, possibly on another core and so a few frames late).
 *   The node keeps the last FILTER_NODE_PAIR_FRAMES frames' steps; it goes back
 *   to the frame, takes both measurements there in one hkf_update_pair step
 *   (each with its own model's Eq. 8 curves; the second alone when the first
 *   found no face or measures |yaw| >= pair_second_alone_from_yaw) and redoes the frames after it.
 *   One pose per frame: the frame's pose went out with the first model's measurement, so the
 *   correction goes with the next frame's pose, and no second pose for the frame steps back. Where
 *   the first measures |yaw| >= pair_second_alone_from_yaw (its measurement set aside once the
 *   second's comes) and the second's measurements come promptly, the first's waits
 *   (second_model_awaits): the node predicts and publishes the posterior when the second's is fused.
 *   A frame where the first model gave no pose waits the same way where the track is predicted at |yaw| >=
 *   pair_second_alone_from_yaw (beyond the first's reach, or hkf-estimator did not run it there:
 *   --second-alone-from-yaw); its deadline publishes the prediction. Where the first model found no face
 *   elsewhere (its pose was a prediction) and the frame is the newest, the posterior with the second's is
 *   published at once too, at that frame's time. A second measurement
 *   older than the kept frames (its seq and utime are one of the followed publisher's last frames)
 *   is counted, not used. A restart, a command or a clock resync forgets the kept frames. Two models
 *   disagree by an amount that changes with the turn (docs/evaluation.md): the second's angles are
 *   moved onto the first's frame by their difference learnt as a piecewise-linear curve in the
 *   second's angle (model_alignment.h) over about the last FILTER_NODE_ALIGN_FRAMES frames both
 *   measured, so that the pose does not step when the second model comes and goes or where the
 *   first model's reach ends, and the first's innovations do not read the gap as motion.
 * - position: a measurement's x, y, z (z > 0: measured) go through
 *   libhkf's position filter (hkf/hkf_position.h), with R scaled by its
 *   model's position_r_scale (node_config.h: 1 for the face mesh's fit, 25 for
 *   a position from the face box). Where the first model measured no
 *   position in a frame (the mesh folds at a profile), a second model's
 *   position of that frame stands in, with its own model's scale, moved onto the first's
 *   by the running mean of their difference (model_offset.h), while the frame is kept
 *   (FILTER_NODE_PAIR_FRAMES). A position is taken within FILTER_NODE_MIN_Z <= z <=
 *   HKF_MAX_ABS_POSITION and |x|, |y| <= HKF_MAX_ABS_POSITION (z = 0: none measured; others are
 *   counted as bad_positions), and passes the position filter's outlier gate. The pose carries
 *   the filtered position at its time (hkf_position_extrapolate: coasting at its rate for up to
 *   the position's max_dt, then held with rate 0, its variance growing - the position's own
 *   staleness, apart from the angles' status), within the same range, and its centre; RECENTER
 *   sets the centre on the position last published, RESET forgets it and the models' offset, a
 *   restart keeps it.
 */
#ifndef FILTER_NODE_H
#define FILTER_NODE_H

#include <stdint.h>

#include "hkf/hkf.h"
#include "hkf/hkf_position.h"
#include "hkf_head_pose_measurement_t.h"
#include "node_position.h"
#include "node_rest.h"
#include "hkf_head_pose_t.h"
#include "hkf_tracker_command_t.h"
#include "node_config.h"
#include "resolved_models.h"
#include "second_model.h"
#include "stream_admission.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    unsigned long received;        /* measurements handled */
    unsigned long published;       /* poses produced (including extrapolated) */
    unsigned long extrapolated;    /* of those, extrapolated */
    unsigned long without_face;    /* valid = false */
    unsigned long out_of_order;    /* rejected: utime older than the last */
    unsigned long duplicates;      /* rejected: utime equal to the last */
    unsigned long bad_values;      /* rejected: non-finite or out-of-range angles */
    unsigned long bad_positions;   /* positions not taken: non-finite, z < FILTER_NODE_MIN_Z (but not 0), beyond the range */
    unsigned long positions_gated; /* positions the position filter's outlier gate refused */
    unsigned long decode_errors;   /* messages that did not decode */
    unsigned long restarts;        /* tracks restarted after a gap or a model change */
    unsigned long clock_jumps;     /* rejected: capture time disagrees with arrival time */
    unsigned long clock_resyncs;   /* the capture clock moved and the node followed it */
    unsigned long other_publisher; /* rejected: seq does not continue the followed estimator's */
    unsigned long unknown_models;  /* measurements whose model is not in the table */
    unsigned long silences;        /* the estimator fell silent for coast_time: LOST published */
    unsigned long paired;          /* second-model measurements fused into their frame */
    unsigned long unpaired;        /* second-model measurements not used: too late, no face, or a frame's third */
    unsigned long gross_refused;   /* of the fused frames, a reading refused as a gross error (FILTER_NODE_GROSS_DEG) */
    unsigned long awaited;         /* frames whose first measurement waited for the second's (second_model_awaits) */
    unsigned long awaits_expired;  /* of those, published without it: its deadline passed, or a later frame came */
    unsigned long commands;        /* commands and live settings applied */
    unsigned long settings_saved;  /* SAVE_SETTINGS that wrote the user's config file (the live runner's) */
    unsigned long settings_unsaved; /* SAVE_SETTINGS that failed */
} filter_node_counts_t;

#define FILTER_NODE_QUEUED (FILTER_NODE_PAIR_FRAMES + 1) /* waiting frames settled at once, and the frame after them */

typedef struct {
    const node_config_t *config;
    resolved_models_t models;         /* the config's models, resolved once (resolved_models.h) */
    hkf_filter_t filter;
    hkf_calibration_t calibration;    /* beside the filter: its noise level (hkf/hkf_calibration.h) */
    node_rest_t rest;                 /* the player's rest: HOLD's wander and the centre (node_rest.h) */
    char model[NODE_MODEL_NAME_MAX];  /* the model the filter is set up for */
    /* Read by the scheduling (node_schedule.h): admission (the time reference) and lost_published;
     * by the runners: counts (the summary). The runners write one field only: counts.decode_errors,
     * for what does not decode before it reaches the node. */
    stream_admission_t admission;     /* the publisher followed and the time reference (stream_admission.h) */
    int64_t last_measurement_utime;   /* capture time of the last valid measurement used */
    int64_t lost_published;           /* LOST poses published in the current silence */
    int64_t seq;
    int64_t published_utime;          /* the last pose's utime: none later is older (INT64_MIN: none on this clock) */
    second_model_t second;            /* the kept frames and the second model's offset (second_model.h) */
    hkf_real_t rest_dt;               /* s of frames without a face not yet given to the rest: their second
                                       * model's measurement may still come (a face only it sees) */
    hkf_head_pose_t queued[FILTER_NODE_QUEUED];  /* poses due at once, in order (filter_node_queued) */
    int queued_first, queued_count;
    node_position_t position;         /* the head's position, a second model's standing in (node_position.h) */
    filter_node_counts_t counts;
} filter_node_t;

/* 0, or a hkf_result_t when the base settings are invalid. The models' settings and the pair's
 * rule are resolved here (resolved_models.h): a config changed later needs filter_node_init again. */
int filter_node_init(filter_node_t *node, const node_config_t *config);


/* Poses are never stamped earlier than the pose before them on one capture clock, a silence's LOST pose
 * aside: a measurement whose frame arrived after --rate ticks went past its capture time is published
 * as its posterior moved on to the last tick's time (flagged extrapolated), and ticks at or before a
 * published pose are skipped. A LOST pose is stamped when it fell due (filter_node_silence); a frame
 * captured before that and arriving after it keeps its own stamp. */

/* Handles one measurement that arrived at arrival_utime (the receive clock:
 * a monotonic clock live, the log's event timestamp offline), in one pass: admission (stream_admission.h;
 * a second model's measurement of a frame is told apart first), the angles (a first model's step, or a
 * second model's fused into its frame: second_model.h), the position (node_position.h), the pose.
 * Returns 1 when *pose is to be published: the first of the poses the message makes due (waiting frames settled
 * before it go first); the others wait in the queue, for filter_node_await_next (node_schedule_next calls it),
 * which the caller calls after each message until it returns 0. */
int filter_node_receive(filter_node_t *node, const hkf_head_pose_measurement_t *m, int64_t arrival_utime,
                        hkf_head_pose_t *pose);

/* One pose per frame whatever the second model does: a frame whose first measurement waits for the second's
 * (second_model_awaits) is published by its deadline (second_model_deadline: most of a frame period after it
 * arrived), with the second's answer or, when none came, from its own measurement; a later frame that
 * arrives first settles it the same way. Where one call has more than one pose to publish (waiting frames
 * settled by a later one), the first is its *pose and the others wait in order in the queue. */

/* The arrival time at which a waiting frame is due (second_model_deadline), 1 when poses are queued (due
 * now), or 0: none. */
int64_t filter_node_await_due(const filter_node_t *node);

/* The next queued pose (*due: now), or else the oldest waiting frame's if its deadline (*due) is at or before
 * `now` (settled without its answer: second_model_settle). Returns 1 when *pose is to be published; called
 * until 0. A command, a restart or a new clock settles the waiting frames too, their poses queued. */
int filter_node_await_next(filter_node_t *node, int64_t now, hkf_head_pose_t *pose, int64_t *due);

/* Handles one measurement by its capture time alone; returns 1 when *pose is to be published. */
int filter_node_measurement(filter_node_t *node, const hkf_head_pose_measurement_t *m, hkf_head_pose_t *pose);

/* The pose at capture-clock time utime (>= the last measurement's), for
 * publishing between measurements; returns 1 when *pose is to be published. */
int filter_node_extrapolate(filter_node_t *node, int64_t utime, hkf_head_pose_t *pose);

#define FILTER_NODE_LOST_REPEAT_US 1000000LL /* while silent, LOST again every second for late subscribers */

/* The live node's watchdog, called whenever no message came for a while: the
 * followed estimator has sent nothing since its last measurement arrived (it
 * died, hung, or its camera stopped). After coast_time of silence, a LOST pose
 * (the last angles held, rates zero, flagged extrapolated), then again every
 * FILTER_NODE_LOST_REPEAT_US while the silence lasts. The filter is not
 * changed: a late frame is still filtered as usual, and after max_dt the
 * next measurement restarts the track. Returns 1 when *pose is to be published. */
int filter_node_silence(filter_node_t *node, int64_t arrival_utime, hkf_head_pose_t *pose);

/* When (arrival clock) the next LOST pose of a silence is due, or 0 (no track, or a capture stamp so
 * near the clock's end that no LOST pose could be stamped):
 * the live loop wakes then. The pose is stamped that long after the last
 * measurement's capture time, so the live node and --offline agree. */
int64_t filter_node_silence_due(const filter_node_t *node);

/* The status that goes with the last pose (tracker_status_t): the player's rest (node_rest.h). */
void filter_node_status(const filter_node_t *node, const hkf_head_pose_t *pose, hkf_tracker_status_t *status);

/* RECENTER or RESET (each asks for a rest: node_rest.h); returns 0, or -1 for an unknown command.
 * SAVE_SETTINGS is the live runner's (it writes a file: node_settings_live.h): -1 here. */
int filter_node_command(filter_node_t *node, const hkf_tracker_command_t *command);

#ifdef __cplusplus
}
#endif

#endif /* FILTER_NODE_H */
