/* view_tracker.c - see view_tracker.h. */
#define _POSIX_C_SOURCE 200809L

#include "view_tracker.h"

#include <stdio.h>
#include <string.h>

#include "clocks.h"
#include "hkf_camera_picture_t.h"
#include "hkf_picture_request_t.h"
#include "hkf_tracker_command_t.h"
#include "hkf_tracker_setting_t.h"
#include "lcm_wait.h"
#include "message_decode.h"
#include "view_door.h"
#include "view_events.h"
#include "view_listen.h"

#define ASK_EVERY_US 500000 /* the estimator sends pictures until 2 s after the last request */

static void on_raw(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    view_tracker_t *view = user;
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
    view_tracker_t *view = user;
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
    view_tracker_t *view = user;
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
    view_tracker_t *view = user;
    hkf_camera_picture_t p;
    char json[VIEW_FEED_EVENT_SIZE];
    (void)channel;
    if (rbuf->data_size > INT32_MAX || message_decode_picture(rbuf->data, (int)rbuf->data_size, &p) != 0) {
        ++view->decode_errors;
        return;
    }
    if (p.jpeg_size > 0 && view_feed_keep_picture(&view->feed, p.jpeg, (size_t)p.jpeg_size) == 0 &&
        view_event_picture(view->feed.pictures, p.utime, p.seq, json, sizeof json) > 0) {
        view_feed_write(&view->feed, json);
    }
    hkf_camera_picture_t_decode_cleanup(&p);
}

/* A page's command to hkf-filter: recenter, reset and save as tracker_command_t; stillness (its value) as
 * tracker_setting_t, which the node checks as its config file's line. */
static int command(void *user, const char *verb, double value, char *reason, size_t reason_size)
{
    view_tracker_t *view = user;
    hkf_tracker_command_t c;
    hkf_tracker_setting_t setting;
    char text[32];
    int sent;
    c.utime = setting.utime = clock_wall_us();
    c.command = strcmp(verb, "recenter") == 0 ? HKF_TRACKER_COMMAND_T_RECENTER
                : strcmp(verb, "reset") == 0  ? HKF_TRACKER_COMMAND_T_RESET
                : strcmp(verb, "save") == 0   ? HKF_TRACKER_COMMAND_T_SAVE_SETTINGS
                                              : 0;
    if (c.command == 0 && strcmp(verb, "stillness") != 0) {
        snprintf(reason, reason_size, "hkf-view: unknown command (recenter, reset, stillness?value=X, save)\n");
        return -1;
    }
    if (c.command == 0 && !(value >= 0.0 && value <= 100.0)) {
        snprintf(reason, reason_size, "hkf-view: stillness is from 0 to 100\n");
        return -1;
    }
    snprintf(text, sizeof text, "%.6g", value);
    setting.key = (char *)"stillness";
    setting.value = text;
    pthread_mutex_lock(&view->publish_lock);
    sent = c.command != 0 ? hkf_tracker_command_t_publish(view->lcm, "HEAD_TRACKER_CMD", &c)
                          : hkf_tracker_setting_t_publish(view->lcm, "HEAD_TRACKER_CMD", &setting);
    pthread_mutex_unlock(&view->publish_lock);
    if (sent != 0) snprintf(reason, reason_size, "hkf-view: publishing the command failed\n");
    return sent != 0 ? -1 : 0;
}

static int subscribe(view_tracker_t *view)
{
    return lcm_wait_subscribe(view->lcm, "HEAD_POSE_RAW", on_raw, view, "hkf-view") == NULL ||
                   lcm_wait_subscribe(view->lcm, "HEAD_POSE", on_pose, view, "hkf-view") == NULL ||
                   lcm_wait_subscribe(view->lcm, "HEAD_POSE_STATUS", on_status, view, "hkf-view") == NULL ||
                   lcm_wait_subscribe(view->lcm, "HEAD_POSE_PICTURE", on_picture, view, "hkf-view") == NULL
               ? -1
               : 0;
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

int view_tracker_start(view_tracker_t *v, lcm_t *lcm, const view_settings_t *settings)
{
    char host[64], reason[256], assets[4096];
    unsigned port;
    memset(v, 0, sizeof *v);
    v->lcm = lcm;
    v->settings = *settings;
    if (view_listen_parse(settings->listen, host, sizeof host, &port, reason, sizeof reason) != 0) {
        fprintf(stderr, "hkf-view: --listen %s\n", reason);
        return -1;
    }
    if (settings->assets != NULL) {
        snprintf(assets, sizeof assets, "%s", settings->assets);
    } else {
        view_default_assets(assets, sizeof assets);
    }
    if (view_door_open(&v->server.door, host, port) != 0 || view_feed_init(&v->feed) != 0 ||
        pthread_mutex_init(&v->publish_lock, NULL) != 0 || subscribe(v) != 0 ||
        view_server_start(&v->server, assets, &v->feed, settings->max_viewers, command, v) != 0) {
        return -1;
    }
    say_where(&v->server.door);
    printf("hkf-view: the page's files from %s\n", assets);
    fflush(stdout);
    return 0;
}

void view_tracker_line(view_tracker_t *v, const char *line)
{
    char json[VIEW_FEED_EVENT_SIZE];
    if (view_event_line(line, json, sizeof json) > 0) view_feed_write(&v->feed, json);
}

void view_tracker_tick(view_tracker_t *v, int64_t now_us)
{
    hkf_picture_request_t r;
    if (now_us < v->next_ask_us) return;
    v->next_ask_us = now_us + ASK_EVERY_US;
    if (view_server_viewers(&v->server) == 0) return;
    r.utime = clock_wall_us();
    r.fps = (float)v->settings.picture_fps;
    r.width = (int16_t)v->settings.picture_width;
    pthread_mutex_lock(&v->publish_lock);
    (void)hkf_picture_request_t_publish(v->lcm, "HEAD_POSE_PICTURE_REQUEST", &r);
    pthread_mutex_unlock(&v->publish_lock);
}

void view_tracker_stop(view_tracker_t *v)
{
    view_server_stop(&v->server);
    printf("hkf-view: %ld commands, %ld requests refused, %ld undecodable messages, %ld events a slow viewer skipped\n",
           v->server.commands, v->server.refused, v->decode_errors, v->feed.skipped);
    view_feed_destroy(&v->feed);
    (void)pthread_mutex_destroy(&v->publish_lock);
}
