/* node_rest.c - see node_rest.h. */
#include "node_rest.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

int node_rest_init(node_rest_t *r, const hkf_rest_settings_t *s)
{
    memset(r, 0, sizeof *r);
    const int result = hkf_rest_init(&r->rest, s);
    return result != HKF_OK ? result : hkf_rest_start(&r->rest);
}

void node_rest_recentered(node_rest_t *r, const hkf_filter_t *f)
{
    if (hkf_get_status(f) != HKF_STATUS_UNINITIALIZED && hkf_get_center(f, r->center) == HKF_OK) {
        r->center_set = 1; /* without a track nothing was centred: the rest's mean will be */
    }
    (void)hkf_rest_start(&r->rest);
}

void node_rest_forget(node_rest_t *r)
{
    r->measured = 0;
    r->center_set = 0;
    (void)hkf_rest_start(&r->rest);
}

void node_rest_keep(const node_rest_t *r, hkf_filter_t *f)
{
    if (r->measured) {
        (void)hkf_set_wander(f, r->result.wander);
    }
    if (r->center_set) {
        (void)hkf_set_center(f, r->center);
    }
}

int node_rest_set_stillness(node_rest_t *r, hkf_filter_t *f, hkf_real_t stillness)
{
    const int result = hkf_rest_set_stillness(&r->rest, stillness);
    if (result == HKF_OK && r->measured) {
        (void)hkf_rest_get_result(&r->rest, &r->result); /* the measured rest's, its wander rescaled */
        node_rest_keep(r, f);
    }
    return result;
}

void node_rest_describe_measured(const node_rest_t *r, char *text, size_t size)
{
    const hkf_rest_result_t *m = &r->result;
    snprintf(text, size, "rest measured: wander %.3f deg^2 (pitch yaw roll: spread %.3f %.3f %.3f deg^2, noise %.3f %.3f "
                         "%.3f deg^2, drift %.2f %.2f %.2f deg^2/s), centre %.1f %.1f %.1f deg",
             (double)m->wander, (double)m->spread[0], (double)m->spread[1], (double)m->spread[2], (double)m->noise[0],
             (double)m->noise[1], (double)m->noise[2], (double)m->drift[0], (double)m->drift[1], (double)m->drift[2],
             (double)m->center[0], (double)m->center[1], (double)m->center[2]);
}

void node_rest_describe_spoiled(const node_rest_t *r, char *text, size_t size)
{
    const hkf_rest_result_t *m = &r->rest.last_refused;
    unsigned spoiled = 0u;
    (void)hkf_rest_get_progress(&r->rest, NULL, NULL, &spoiled, NULL);
    if (r->refused_last) {
        double excess = 0.0, drift = 0.0;
        int a;
        for (a = 0; a < 3; ++a) {
            excess = fmax(excess, (double)m->spread[a] - (double)m->noise[a]);
            drift = fmax(drift, (double)m->drift[a]);
        }
        snprintf(text, size, "the rest was refused: the head moved through it (spread %.2f deg^2 beyond its noise, "
                             "drift %.1f deg^2/s; a rest keeps within %.1f and %.1f) (%u since it was asked for); "
                             "keep still for %.1f s",
                 excess, drift, HKF_REST_MOVED_WANDER, HKF_REST_MOVED_DRIFT, spoiled, (double)r->rest.settings.rest_time);
        return;
    }
    snprintf(text, size, "the rest was spoiled by a move (%u since it was asked for); keep still for %.1f s", spoiled,
             (double)r->rest.settings.rest_time);
}

void node_rest_take(node_rest_t *r, hkf_filter_t *f, const hkf_real_t *z, hkf_real_t dt)
{
    const unsigned refused_before = r->rest.refused;
    switch (hkf_rest_update(&r->rest, z, dt)) {
    case HKF_REST_MEASURED:
        (void)hkf_rest_get_result(&r->rest, &r->result);
        r->measured = 1;
        memcpy(r->center, r->result.center, sizeof r->center); /* the rest's mean: the player's centre now */
        r->center_set = 1;
        ++r->measured_count;
        node_rest_keep(r, f);
        break;
    case HKF_REST_SPOILED:
        ++r->spoiled_count;
        r->refused_last = r->rest.refused != refused_before; /* refused at its end, not spoiled by a move */
        r->refused_count += (unsigned long)r->refused_last;
        break;
    default: /* measuring, idle, or a value the filter refused too */
        break;
    }
}

void node_rest_status(const node_rest_t *r, const hkf_filter_t *f, int64_t utime, int64_t seq,
                      hkf_tracker_status_t *status)
{
    hkf_real_t progress = 0, wander = 0;
    unsigned spoiled = 0u;
    int measuring = 0, measured = 0, a;
    (void)hkf_rest_get_progress(&r->rest, &measuring, &progress, &spoiled, &measured);
    (void)hkf_get_wander(f, &wander);
    memset(status, 0, sizeof *status);
    status->utime = utime;
    status->pose_seq = seq;
    status->rest = measuring ? HKF_TRACKER_STATUS_T_RESTING : measured ? HKF_TRACKER_STATUS_T_MEASURED
                                                                       : HKF_TRACKER_STATUS_T_NO_REST;
    status->rest_progress = (float)progress;
    status->rest_time = (float)r->rest.settings.rest_time;
    status->rests_spoiled = (int32_t)spoiled;
    status->wander_measured = r->measured != 0;
    status->stillness = (float)r->rest.settings.stillness;
    status->wander = (float)wander;
    for (a = 0; a < 3; ++a) {
        status->rest_spread[a] = r->measured ? (float)r->result.spread[a] : 0.0f;
        status->rest_noise[a] = r->measured ? (float)r->result.noise[a] : 0.0f;
        status->rest_drift[a] = r->measured ? (float)r->result.drift[a] : 0.0f;
        status->rest_center[a] = r->measured ? (float)r->result.center[a] : 0.0f;
    }
}
