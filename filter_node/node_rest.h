/*
 * node_rest.h - the player's rest in hkf-filter (libhkf's hkf/hkf_rest.h): asked for when tracking
 * starts and at every RECENTER or RESET. A rest measured hands its wander to the filter (HOLD's,
 * hkf_set_wander: stillness x the measured one) and makes its mean pose the centre; a rest spoiled by a
 * move is not taken, is said, and is asked for again. Until a rest is measured the filter keeps its
 * still_wander, a low built-in value that keeps raw's onset. The status message (tracker_status_t)
 * says where the rest stands.
 */
#ifndef NODE_REST_H
#define NODE_REST_H

#include <stddef.h>

#include "hkf/hkf.h"
#include "hkf/hkf_rest.h"
#include "hkf_tracker_status_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The node's one owner of the view's centre and HOLD's wander: whatever set them last (a rest measured, a
 * RECENTER) is what the filter gets back after it is set up anew or restored to an earlier step (a model
 * change, a second model's frames redone), so that a replay never undoes a player's command. */
typedef struct {
    hkf_rest_t rest;
    hkf_rest_result_t result; /* the last rest measured */
    int measured;             /* result holds one: its wander is HOLD's */
    hkf_real_t center[3];     /* the centre the player set last (a rest's mean or a RECENTER), if center_set */
    int center_set;
    unsigned long measured_count, spoiled_count; /* rests measured and spoiled so far, for the runners to say */
    int refused_last;         /* the last spoiled rest was refused at its end: the head moved through it */
    unsigned long refused_count; /* of the spoiled, rests refused so */
} node_rest_t;

/* The settings taken (checked by the config), and the rest asked for: tracking starts. */
int node_rest_init(node_rest_t *r, const hkf_rest_settings_t *s);

/* RECENTER: the centre f was just recentred on becomes the player's (it is kept over replays), and a new
 * rest is asked for (the last one's wander stays until it is measured). */
void node_rest_recentered(node_rest_t *r, const hkf_filter_t *f);

/* RESET: the last rest and the centre forgotten too, and a new rest asked for. */
void node_rest_forget(node_rest_t *r);

/* One first-model frame the filter took: z its measurement (NULL: no face), dt its step. A rest
 * measured is handed to f (node_rest_keep); a spoiled one is counted. */
void node_rest_take(node_rest_t *r, hkf_filter_t *f, const hkf_real_t *z, hkf_real_t dt);

/* The player's centre (the last rest's mean or RECENTER's) and the measured rest's wander given to f again,
 * after f was set up anew or restored to an earlier step (a model change, a second model's frames redone).
 * Nothing of what was never set. */
void node_rest_keep(const node_rest_t *r, hkf_filter_t *f);

/* The player's stillness turned while tracking (node_settings_live.h): the rest takes it, and a measured
 * rest's wander, stillness x its measured one, goes to f at once. A hkf_result_t. */
int node_rest_set_stillness(node_rest_t *r, hkf_filter_t *f, hkf_real_t stillness);

/* What a runner says of a rest measured (the wander, the spread, noise and drift per axis, the centre) or
 * spoiled, into text. */
void node_rest_describe_measured(const node_rest_t *r, char *text, size_t size);
void node_rest_describe_spoiled(const node_rest_t *r, char *text, size_t size);

/* The status that goes with a pose (its utime and seq), the wander f takes. */
void node_rest_status(const node_rest_t *r, const hkf_filter_t *f, int64_t utime, int64_t seq,
                      hkf_tracker_status_t *status);

#ifdef __cplusplus
}
#endif

#endif /* NODE_REST_H */
