/*
 * hkf-view - the live view: serves one page (view_server.h) that shows, while hkf tracks, the camera picture
 * with the face's box and the head's axes, the raw and filtered pose as traces, hkf-track's status line and
 * the player's rest, and sends the page's commands to hkf-filter. It reads the tracker's LCM channels, so it
 * views a tracker however it was started; hkf-track --view starts it beside the others.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <lcm/lcm.h>

#include "arguments.h"
#include "clocks.h"
#include "hkf_camera_picture_t.h"
#include "hkf_picture_request_t.h"
#include "hkf_tracker_command_t.h"
#include "lcm_file_url.h"
#include "lcm_wait.h"
#include "message_decode.h"
#include "track_monitor.h"
#include "view_events.h"
#include "view_listen.h"
#include "view_server.h"

typedef struct {
    const char *listen, *lcm_url, *assets;
    int max_viewers, picture_width;
    double seconds, picture_fps;
} view_options_t;

typedef struct {
    lcm_t *lcm;
    view_feed_t feed;
    track_monitor_t monitor;
    pthread_mutex_t publish_lock; /* commands come from the viewers' threads */
    long decode_errors;
} view_t;

static void usage(FILE *to)
{
    fprintf(to,
            "usage: hkf-view [--listen [HOST:]PORT] [--lcm-url URL] [options]\n"
            "The live view of a running tracker, in a browser: the camera picture with the face's box and the\n"
            "head's axes, the raw and filtered pose over the last 10 s, the status line and the rest, and\n"
            "buttons to recentre and reset. Open the address it prints.\n"
            "  --listen [HOST:]PORT  where to serve (default 127.0.0.1:" VIEW_DEFAULT_PORT ": this computer only);\n"
            "                    0.0.0.0:PORT opens it to every network this computer is on (a phone beside\n"
            "                    it), and says so\n"
            "  --lcm-url URL     LCM provider (default " LCM_URL_DEFAULT ")\n"
            "  --assets DIR      the page's files (default: share/hkf/view beside bin/, or the source tree's)\n"
            "  --max-viewers N   pages open at once, 1 to 64 (default 8); more are refused\n"
            "  --picture-fps F   camera pictures a second asked of hkf-estimator, 1 to 30 (default 10)\n"
            "  --picture-width W their width in px, 64 to 1280 (default 320)\n"
            "  --seconds S       stop after S s (default: on Ctrl-C)\n"
            "  --help, --version this text; the version\n"
            "Channels: HEAD_POSE_RAW, HEAD_POSE, HEAD_POSE_STATUS and HEAD_POSE_PICTURE in; HEAD_TRACKER_CMD and\n"
            "HEAD_POSE_PICTURE_REQUEST out (docs/programs.md, \"The live view\").\n");
}

/* The command line into o: 0 run, 1 answered (--help, --version), 2 bad (said). */
static int parse(int argc, char **argv, view_options_t *o)
{
    int i;
    for (i = 1; i < argc; ++i) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        double n = 0.0;
        if (argument_help_or_version(a, "hkf-view", usage)) return 1;
        if (v == NULL) {
            fprintf(stderr, "hkf-view: unknown or incomplete argument '%s' (see --help)\n", a);
            return 2;
        }
        ++i;
        if (strcmp(a, "--listen") == 0) {
            o->listen = v;
        } else if (strcmp(a, "--lcm-url") == 0) {
            o->lcm_url = v;
        } else if (strcmp(a, "--assets") == 0) {
            o->assets = v;
        } else if (strcmp(a, "--max-viewers") == 0 && argument_number(v, 1, 64, &n) && n == floor(n)) {
            o->max_viewers = (int)n;
        } else if (strcmp(a, "--picture-fps") == 0 && argument_number(v, 1, 30, &n)) {
            o->picture_fps = n;
        } else if (strcmp(a, "--picture-width") == 0 && argument_number(v, 64, 1280, &n) && n == floor(n)) {
            o->picture_width = (int)n;
        } else if (strcmp(a, "--seconds") == 0 && argument_number(v, 0.001, 1e9, &n)) {
            o->seconds = n;
        } else {
            fprintf(stderr, "hkf-view: bad or unknown argument '%s %s' (see --help)\n", a, v);
            return 2;
        }
    }
    return 0;
}

static void on_raw(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    view_t *view = user;
    hkf_head_pose_measurement_t m;
    char json[VIEW_FEED_EVENT_SIZE];
    (void)channel;
    if (message_decode_measurement(rbuf->data, (int)rbuf->data_size, &m) != 0) {
        ++view->decode_errors;
        return;
    }
    if (view_event_raw(&m, json, sizeof json) > 0) view_feed_write(&view->feed, json);
    hkf_head_pose_measurement_t_decode_cleanup(&m);
}

static void on_pose(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    view_t *view = user;
    hkf_head_pose_t p;
    char json[VIEW_FEED_EVENT_SIZE];
    (void)channel;
    if (message_decode_pose(rbuf->data, (int)rbuf->data_size, &p) != 0) {
        ++view->decode_errors;
        return;
    }
    if (view_event_pose(&p, json, sizeof json) > 0) view_feed_write(&view->feed, json);
}

static void on_status(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    view_t *view = user;
    hkf_tracker_status_t s;
    char json[VIEW_FEED_EVENT_SIZE];
    (void)channel;
    if (hkf_tracker_status_t_decode(rbuf->data, 0, (int)rbuf->data_size, &s) < 0) {
        ++view->decode_errors;
        return;
    }
    if (view_event_status(&s, json, sizeof json) > 0) view_feed_write(&view->feed, json);
}

static void on_picture(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    view_t *view = user;
    hkf_camera_picture_t p;
    char json[VIEW_FEED_EVENT_SIZE];
    (void)channel;
    /* the size is checked before decoding: a picture message is never larger than its largest JPEG and fields */
    if (rbuf->data_size > HKF_CAMERA_PICTURE_T_MAX_JPEG_SIZE + 64 ||
        hkf_camera_picture_t_decode(rbuf->data, 0, (int)rbuf->data_size, &p) < 0) {
        ++view->decode_errors;
        return;
    }
    if (p.jpeg_size > 0 && view_feed_keep_picture(&view->feed, p.jpeg, (size_t)p.jpeg_size) == 0 &&
        view_event_picture(view->feed.pictures, p.utime, p.seq, json, sizeof json) > 0) {
        view_feed_write(&view->feed, json);
    }
    hkf_camera_picture_t_decode_cleanup(&p);
}

/* A page's command: recenter and reset go to hkf-filter as tracker_command_t. */
static int command(void *user, const char *verb, double value, char *reason, size_t reason_size)
{
    view_t *view = user;
    hkf_tracker_command_t c;
    int sent;
    (void)value;
    if (strcmp(verb, "recenter") == 0) {
        c.command = HKF_TRACKER_COMMAND_T_RECENTER;
    } else if (strcmp(verb, "reset") == 0) {
        c.command = HKF_TRACKER_COMMAND_T_RESET;
    } else {
        snprintf(reason, reason_size, "hkf-view: unknown command (recenter, reset)\n");
        return -1;
    }
    c.utime = clock_wall_us();
    pthread_mutex_lock(&view->publish_lock);
    sent = hkf_tracker_command_t_publish(view->lcm, "HEAD_TRACKER_CMD", &c);
    pthread_mutex_unlock(&view->publish_lock);
    if (sent != 0) snprintf(reason, reason_size, "hkf-view: publishing the command failed\n");
    return sent != 0 ? -1 : 0;
}

static int subscribe(view_t *view)
{
    return track_monitor_start(&view->monitor, view->lcm, 1) != 0 ||
                   lcm_wait_subscribe(view->lcm, "HEAD_POSE_RAW", on_raw, view, "hkf-view") == NULL ||
                   lcm_wait_subscribe(view->lcm, "HEAD_POSE", on_pose, view, "hkf-view") == NULL ||
                   lcm_wait_subscribe(view->lcm, "HEAD_POSE_STATUS", on_status, view, "hkf-view") == NULL ||
                   lcm_wait_subscribe(view->lcm, "HEAD_POSE_PICTURE", on_picture, view, "hkf-view") == NULL
               ? -1
               : 0;
}

static void ask_for_pictures(view_t *view, const view_options_t *o)
{
    hkf_picture_request_t r;
    r.utime = clock_wall_us();
    r.fps = (float)o->picture_fps;
    r.width = (int16_t)o->picture_width;
    pthread_mutex_lock(&view->publish_lock);
    (void)hkf_picture_request_t_publish(view->lcm, "HEAD_POSE_PICTURE_REQUEST", &r);
    pthread_mutex_unlock(&view->publish_lock);
}

/* Until a stop request or --seconds: the messages, the status line (once a second; twice while the rest
 * counts down) and, while a viewer is open, the request for pictures twice a second. 0, or 1 (said). */
static int serve(view_t *view, view_server_t *server, const view_options_t *o)
{
    const int64_t started = clock_monotonic_us();
    int64_t last_line = started, next_line = started + 1000000, next_ask = started;
    char line[1024], json[VIEW_FEED_EVENT_SIZE];
    while (!lcm_wait_stop_requested()) {
        const int64_t now = clock_monotonic_us();
        if (o->seconds > 0.0 && (double)(now - started) >= o->seconds * 1e6) break;
        if (lcm_wait_and_handle(view->lcm, lcm_wait_time(next_line < next_ask ? next_line : next_ask, now),
                                "hkf-view") < 0)
            return 1;
        if (clock_monotonic_us() >= next_line) {
            const int64_t at = clock_monotonic_us();
            track_monitor_line(&view->monitor, (double)(at - started) / 1e6, (double)(at - last_line) / 1e6, line,
                               sizeof line);
            if (view_event_line(line, json, sizeof json) > 0) view_feed_write(&view->feed, json);
            last_line = at;
            next_line += track_monitor_resting(&view->monitor) ? 500000 : 1000000;
        }
        if (clock_monotonic_us() >= next_ask) {
            if (view_server_viewers(server) > 0) ask_for_pictures(view, o);
            next_ask += 500000;
        }
    }
    return 0;
}

/* What the start says: where to open it, and what --listen opens. */
static void say_where(const view_door_t *door)
{
    if (strcmp(door->address, "0.0.0.0") == 0) {
        printf("hkf-view: the live view on http://<this computer's address>:%u/ -- open to every network this "
               "computer is on: anyone who can reach port %u sees the camera's picture (commands need the page's "
               "token)\n",
               door->port, door->port);
    } else if (strncmp(door->address, "127.", 4) == 0) {
        printf("hkf-view: the live view on http://%s:%u/ (this computer only)\n", door->address, door->port);
    } else {
        printf("hkf-view: the live view on http://%s:%u/ (open to that address's network)\n", door->address, door->port);
    }
    fflush(stdout);
}

static int run(view_t *view, const view_options_t *o, view_door_t *door)
{
    static view_server_t server;
    char assets[4096];
    int result;
    if (o->assets != NULL) {
        snprintf(assets, sizeof assets, "%s", o->assets);
    } else {
        view_default_assets(assets, sizeof assets);
    }
    server.door = *door;
    if (view_server_start(&server, assets, &view->feed, o->max_viewers, command, view) != 0) {
        view_server_stop(&server);
        return 1;
    }
    say_where(door);
    result = serve(view, &server, o);
    view_server_stop(&server);
    printf("hkf-view: %ld commands, %ld requests refused, %ld undecodable messages, %ld events a slow viewer skipped\n",
           server.commands, server.refused, view->decode_errors, view->feed.skipped);
    return result;
}

int main(int argc, char **argv)
{
    static view_t view;
    view_options_t o = {VIEW_DEFAULT_HOST ":" VIEW_DEFAULT_PORT, LCM_URL_DEFAULT, NULL, 8, 320, 0.0, 10.0};
    view_door_t door;
    lcm_file_url_t log_file;
    char host[64], reason[256];
    unsigned port;
    int result = parse(argc, argv, &o);
    if (result != 0) return result == 1 ? 0 : 2;
    if (view_listen_parse(o.listen, host, sizeof host, &port, reason, sizeof reason) != 0) {
        fprintf(stderr, "hkf-view: --listen %s\n", reason);
        return 2;
    }
    o.lcm_url = lcm_url_resolve(o.lcm_url);
    if (lcm_file_url_check(o.lcm_url, "input", NULL, 0, "hkf-view", &log_file) != 0) return 2;
    if (view_door_open(&door, host, port) != 0 || view_feed_init(&view.feed) != 0 ||
        pthread_mutex_init(&view.publish_lock, NULL) != 0)
        return 1;
    view.lcm = lcm_create(o.lcm_url);
    if (view.lcm == NULL) {
        fprintf(stderr, "hkf-view: cannot open LCM provider '%s'\n", o.lcm_url);
        return 1;
    }
    lcm_wait_stop_on_signals();
    result = subscribe(&view) != 0 ? 1 : run(&view, &o, &door);
    lcm_destroy(view.lcm);
    view_feed_destroy(&view.feed);
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "hkf-view: writing to stdout failed\n");
        return 1;
    }
    return result;
}
