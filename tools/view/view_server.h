/*
 * view_server.h - the live view's HTTP server (libmicrohttpd, a thread per connection): the page and its
 * two assets, the event stream (Server-Sent Events from the feed), the latest camera picture and the
 * commands, each request first checked at the door (view_door.h).
 *   GET  /                the page, with the run's token in it
 *   GET  /view.js, /view.css
 *   GET  /events          text/event-stream: the feed's events, the last ~10 s first (at most max_viewers)
 *   GET  /picture.jpg     the latest camera picture (404 before the first)
 *   POST /command/VERB    recenter, reset, stillness?value=V, save: with the token in X-HKF-Token
 * Anything else is 404 (405 for another method); a foreign Host 421, a foreign Origin or a missing or
 * wrong token 403, a viewer beyond max_viewers 503.
 */
#ifndef VIEW_SERVER_H
#define VIEW_SERVER_H

#include <pthread.h>
#include <stddef.h>

#include "view_door.h"
#include "view_feed.h"

#ifdef __cplusplus
extern "C" {
#endif

#define VIEW_ASSETS 3 /* index.html, view.js, view.css */

typedef struct {
    const char *name; /* as asked for: "/", "/view.js", "/view.css" */
    const char *file; /* in the assets folder */
    const char *type;
    char *body;
    size_t size;
} view_asset_t;

/* What a command does: 0 (done, or sent), or -1 with a reason (at most reason_size characters). */
typedef int (*view_command_fn)(void *user, const char *verb, double value, char *reason, size_t reason_size);

typedef struct {
    view_door_t door;
    view_feed_t *feed;
    view_asset_t asset[VIEW_ASSETS];
    int max_viewers;
    view_command_fn command;
    void *command_user;
    pthread_mutex_t lock; /* viewers, refused, commands */
    int viewers;          /* event streams open now */
    long refused;         /* requests refused at the door */
    long commands;        /* commands carried out */
    struct MHD_Daemon *daemon;
} view_server_t;

/* Reads the page's assets from folder (each at most 1 MiB; the page's "@TOKEN@" becomes the token) and
 * starts serving on door's address and port. 0, or -1 (said on stderr). */
int view_server_start(view_server_t *s, const char *folder, view_feed_t *feed, int max_viewers,
                      view_command_fn command, void *command_user);

/* Event streams open now. */
int view_server_viewers(view_server_t *s);

/* Ends every stream (the feed closes), stops serving, frees the assets. */
void view_server_stop(view_server_t *s);

#ifdef __cplusplus
}
#endif

#endif /* VIEW_SERVER_H */
