/*
 * hkf-view - the live view of a running tracker (view_tracker.h): serves one page that shows, while hkf
 * tracks, the camera picture with the face's box and the head's axes, the raw and filtered pose as traces,
 * the status line and the player's rest, and sends the page's commands to hkf-filter. It reads the tracker's
 * LCM channels, so it views a tracker however it was started; hkf-track --view runs the same view in its own
 * process, with its own status line.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <lcm/lcm.h>

#include "arguments.h"
#include "clocks.h"
#include "lcm_file_url.h"
#include "lcm_wait.h"
#include "track_monitor.h"
#include "view_listen.h"
#include "view_tracker.h"

typedef struct {
    view_settings_t view;
    const char *lcm_url;
    double seconds;
} view_options_t;

static void usage(FILE *to)
{
    fprintf(to,
            "usage: hkf-view [--listen [HOST:]PORT] [--lcm-url URL] [options]\n"
            "The live view of a running tracker, in a browser: the camera picture with the face's box and the\n"
            "head's axes, the raw and filtered pose over the last 10 s, the status line and the rest, and\n"
            "controls: recentre, reset, the stillness knob and saving the settings. Open the address it prints.\n"
            "  --listen [HOST:]PORT  where to serve (default 127.0.0.1:" VIEW_DEFAULT_PORT ": this computer only);\n"
            "                    0.0.0.0:PORT opens it to every network this computer is on (a phone beside\n"
            "                    it), and says so\n"
            "  --lcm-url URL     LCM provider (default " LCM_URL_DEFAULT ")\n"
            "  --assets DIR      the page's files (default: share/hkf/view beside bin/, or the source tree's)\n"
            "  --max-viewers N   pages open at once, 1 to 64 (default 8); more are refused\n"
            "  --picture-fps F   camera pictures a second asked of hkf-estimator, 1 to 30 (default 12)\n"
            "  --picture-width W their width in px, 64 to 1280 (default 320)\n"
            "  --seconds S       stop after S s (default: on Ctrl-C)\n"
            "  --help, --version this text; the version\n"
            "Channels: HEAD_POSE_RAW, HEAD_POSE, HEAD_POSE_STATUS and HEAD_POSE_PICTURE in; HEAD_TRACKER_CMD and\n"
            "HEAD_POSE_PICTURE_REQUEST out (docs/programs.md, \"The live view\").\n");
}

/* 1 when text is a [HOST:]PORT to listen on; 0 (said) otherwise. */
static int listen_ok(const char *text)
{
    char host[64], reason[256];
    unsigned port;
    if (view_listen_parse(text, host, sizeof host, &port, reason, sizeof reason) == 0) return 1;
    fprintf(stderr, "hkf-view: --listen %s\n", reason);
    return 0;
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
            o->view.listen = v;
        } else if (strcmp(a, "--lcm-url") == 0) {
            o->lcm_url = v;
        } else if (strcmp(a, "--assets") == 0) {
            o->view.assets = v;
        } else if (strcmp(a, "--max-viewers") == 0 && argument_number(v, 1, 64, &n) && n == floor(n)) {
            o->view.max_viewers = (int)n;
        } else if (strcmp(a, "--picture-fps") == 0 && argument_number(v, 1, 30, &n)) {
            o->view.picture_fps = n;
        } else if (strcmp(a, "--picture-width") == 0 && argument_number(v, 64, 1280, &n) && n == floor(n)) {
            o->view.picture_width = (int)n;
        } else if (strcmp(a, "--seconds") == 0 && argument_number(v, 0.001, 1e9, &n)) {
            o->seconds = n;
        } else {
            fprintf(stderr, "hkf-view: bad or unknown argument '%s %s' (see --help)\n", a, v);
            return 2;
        }
    }
    return listen_ok(o->view.listen) ? 0 : 2;
}

/* Until a stop request or --seconds: the messages, the status line (once a second; twice while the rest
 * counts down) and the view's requests for pictures. 0, or 1 (said). */
static int serve(lcm_t *lcm, view_tracker_t *view, track_monitor_t *monitor, const view_options_t *o)
{
    const int64_t started = clock_monotonic_us();
    int64_t last_line = started, next_line = started + 1000000;
    char line[1024];
    while (!lcm_wait_stop_requested()) {
        const int64_t now = clock_monotonic_us();
        if (o->seconds > 0.0 && (double)(now - started) >= o->seconds * 1e6) break;
        if (lcm_wait_and_handle(lcm, lcm_wait_time(next_line, now), "hkf-view") < 0) return 1;
        if (clock_monotonic_us() >= next_line) {
            const int64_t at = clock_monotonic_us();
            track_monitor_line(monitor, (double)(at - started) / 1e6, (double)(at - last_line) / 1e6, line, sizeof line);
            view_tracker_line(view, line);
            last_line = at;
            next_line += track_monitor_resting(monitor) ? 500000 : 1000000;
        }
        view_tracker_tick(view, clock_monotonic_us());
    }
    return 0;
}

int main(int argc, char **argv)
{
    static view_tracker_t view;
    static track_monitor_t monitor;
    view_options_t o = {VIEW_DEFAULT_SETTINGS, LCM_URL_DEFAULT, 0.0};
    lcm_file_url_t log_file;
    lcm_t *lcm;
    int result = parse(argc, argv, &o);
    if (result != 0) return result == 1 ? 0 : 2;
    o.lcm_url = lcm_url_resolve(o.lcm_url);
    if (lcm_file_url_check(o.lcm_url, "input", NULL, 0, "hkf-view", &log_file) != 0) return 2;
    lcm = lcm_create(o.lcm_url);
    if (lcm == NULL) {
        fprintf(stderr, "hkf-view: cannot open LCM provider '%s'\n", o.lcm_url);
        return 1;
    }
    lcm_wait_stop_on_signals();
    if (track_monitor_start(&monitor, lcm, 1) != 0 || view_tracker_start(&view, lcm, &o.view) != 0) {
        result = 1;
    } else {
        result = serve(lcm, &view, &monitor, &o);
    }
    view_tracker_stop(&view);
    lcm_destroy(lcm);
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "hkf-view: writing to stdout failed\n");
        return 1;
    }
    return result;
}
