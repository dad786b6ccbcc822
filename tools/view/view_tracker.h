/*
 * view_tracker.h - the live view of a running tracker, beside whatever owns the LCM loop (hkf-view, or
 * hkf-track --view in its own process): the tracker's messages into the view's feed (view_events.h), the
 * page's commands out to hkf-filter, camera pictures asked of hkf-estimator twice a second while a viewer is
 * open, and the server (view_server.h). The owner handles LCM and hands over its status line.
 */
#ifndef VIEW_TRACKER_H
#define VIEW_TRACKER_H

#include <pthread.h>
#include <stdint.h>

#include <lcm/lcm.h>

#include "view_feed.h"
#include "view_listen.h"
#include "view_server.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    const char *listen;  /* [HOST:]PORT (view_listen.h) */
    const char *assets;  /* the page's folder, or NULL: view_default_assets */
    int max_viewers;     /* 1 to 64 */
    double picture_fps;  /* camera pictures a second asked for, 1 to 30 */
    int picture_width;   /* px, 64 to 1280 */
} view_settings_t;

#define VIEW_DEFAULT_SETTINGS {VIEW_DEFAULT_HOST ":" VIEW_DEFAULT_PORT, NULL, 8, 12.0, 320}

typedef struct {
    lcm_t *lcm;
    view_settings_t settings;
    view_feed_t feed;
    view_server_t server;
    pthread_mutex_t publish_lock; /* commands come from the viewers' threads */
    long decode_errors;
    int64_t next_ask_us;
} view_tracker_t;

/* Subscribes to the tracker's channels on lcm and starts serving; says where to open it. 0, or -1 (said). A
 * view that started must be stopped. */
int view_tracker_start(view_tracker_t *v, lcm_t *lcm, const view_settings_t *settings);

/* The owner's status line (hkf-track's, as its terminal shows it) to the page. */
void view_tracker_line(view_tracker_t *v, const char *line);

/* Between LCM waits (now_us on the monotonic clock): asks for pictures twice a second while a viewer is open. */
void view_tracker_tick(view_tracker_t *v, int64_t now_us);

/* Ends the viewers' streams and stops serving; says what it counted. */
void view_tracker_stop(view_tracker_t *v);

#ifdef __cplusplus
}
#endif

#endif /* VIEW_TRACKER_H */
