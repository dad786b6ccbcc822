/* track_options.c - see track_options.h. */
#define _POSIX_C_SOURCE 200809L

#include "track_options.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "arguments.h"
#include "lcm_file_url.h"
#include "view_listen.h"

enum option_kind { OPTION_FLAG, OPTION_TEXT };

typedef struct {
    const char *name;
    enum option_kind kind;
    size_t offset; /* of the int (a flag) or the const char * (a text) in track_options_t */
} option_t;

#define TEXT(name, field) {name, OPTION_TEXT, offsetof(track_options_t, field)}
#define FLAG(name, field) {name, OPTION_FLAG, offsetof(track_options_t, field)}

static const option_t options[] = {
    TEXT("--camera", camera),           TEXT("--source", source),
    FLAG("--realtime", realtime),       TEXT("--model", model),
    TEXT("--detector", detector),       TEXT("--second-model", second_model),
    TEXT("--config", config),           TEXT("--rate", rate),
    TEXT("--stillness", stillness),
    FLAG("--opentrack", opentrack),     TEXT("--opentrack-host", opentrack_host),
    TEXT("--opentrack-port", opentrack_port), TEXT("--opentrack-args", opentrack_args),
    TEXT("--flightgear", flightgear),   TEXT("--flightgear-args", flightgear_args),
    TEXT("--view", view),
    TEXT("--lcm-url", lcm_url),         TEXT("--build", build),
    TEXT("--logs", logs),
};

static void usage(FILE *to)
{
    fprintf(to,
            "usage: hkf-track (--camera N | --source FILE) [options]\n"
            "\n"
            "The whole live tracker in one command. Starts hkf-estimator (camera or video ->\n"
            "HEAD_POSE_RAW), hkf-filter (-> HEAD_POSE) and, with --opentrack, hkf-opentrack\n"
            "(-> opentrack's \"UDP over network\" input); prints the camera and filter rates,\n"
            "the capture-to-pose latency and the head pose once a second; stops them all on\n"
            "Ctrl-C (or when a video ends) and prints their summaries. Each program's\n"
            "messages go to a log in --logs.\n"
            "\n"
            "When your face is found, and after each recentre (hkf-cmd recenter), look at the\n"
            "screen's centre and keep still for 2 s while the status line counts down: hkf-filter\n"
            "measures how your resting head pose wanders on this camera and in this light, and\n"
            "holds the view that still at rest (--stillness scales it). A move during it is not\n"
            "taken: the line says so and counts down again.\n"
            "\n"
            "  hkf-track --camera 0 --opentrack            a webcam into opentrack\n"
            "  hkf-track --camera 0 --flightgear 5550      a webcam into FlightGear's cockpit view\n"
            "  hkf-track --source clip.mp4 --realtime      a video standing in for the camera\n"
            "\n"
            "options:\n"
            "  --camera N             camera index (0) or device (/dev/video0)\n"
            "  --source FILE          a video file or a folder of images instead of a camera\n"
            "  --realtime             pace a file at its frame rate, like a camera\n"
            "  --model NAME           head-pose model for hkf-estimator (mesh_pnp, whenet)\n"
            "  --detector NAME        hkf-estimator's face search: retina (default: near, far and\n"
            "                         turned faces), short or full\n"
            "  --second-model NAME    the model hkf-estimator runs beside the first at large turns\n"
            "                         (default whenet; none: the first alone); hkf-filter fuses both\n"
            "  --config FILE          hkf-filter settings file (default: hkf-filter's own search:\n"
            "                         hkf-filter --print-config says where each value came from)\n"
            "  --rate HZ              hkf-filter also publishes extrapolated poses at HZ (0.1-10000)\n"
            "  --stillness X          how still the view holds while you rest: X times the wander\n"
            "                         measured on your start-up rest (default 1; 0-100; 2 stiller,\n"
            "                         0.5 quicker to follow)\n"
            "  --opentrack            also run hkf-opentrack\n"
            "  --opentrack-host HOST  where opentrack listens (default 127.0.0.1)\n"
            "  --opentrack-port PORT  (default 4242)\n"
            "  --opentrack-args ARGS  more hkf-opentrack options, e.g. '--invert yaw'\n"
            "  --flightgear [HOST:]PORT\n"
            "                         also run hkf-opentrack --flightgear: each pose to FlightGear's\n"
            "                         generic input at HOST (default 127.0.0.1) and PORT; start fgfs with\n"
            "                         --data=/usr/share/hkf/flightgear --generic=socket,in,60,,PORT,udp,hkf\n"
            "  --flightgear-args ARGS more options for it, e.g. '--eye -0.2,0.6,-3.5' (the aircraft's\n"
            "                         eye point, m) or '--invert yaw'\n"
            "  --view [HOST:]PORT     also serve the live view (as hkf-view does) at http://HOST:PORT/\n"
            "                         (HOST default 127.0.0.1: this computer only; 0.0.0.0 opens it to\n"
            "                         its networks, e.g. a phone beside it)\n"
            "  --lcm-url URL          LCM provider for all of them (default %s)\n"
            "  --seconds S            stop after this long (default: Ctrl-C, or the source's end)\n"
            "  --build DIR            where the programs were built (default: beside hkf-track)\n"
            "  --logs DIR             folder for the programs' logs (default ./hkf-track-logs)\n"
            "  --help, --version\n"
            "\n"
            "Exit status: 0 when the source ended or Ctrl-C stopped a clean run; 1 when a program\n"
            "failed or its log was lost; 2 for a bad command line or a missing program.\n",
            LCM_URL_DEFAULT);
}

static int bad(const char *what, const char *value)
{
    fprintf(stderr, "hkf-track: %s%s\n", what, value != NULL ? value : "");
    fprintf(stderr, "hkf-track: --help lists the options\n");
    return 2;
}

static const option_t *find_option(const char *arg, const char **inline_value)
{
    const char *equals = strchr(arg, '=');
    size_t length = equals != NULL ? (size_t)(equals - arg) : strlen(arg);
    *inline_value = equals != NULL ? equals + 1 : NULL;
    for (size_t i = 0; i < sizeof options / sizeof options[0]; ++i) {
        if (strlen(options[i].name) == length && strncmp(options[i].name, arg, length) == 0) return &options[i];
    }
    return NULL;
}

/* Reads argv[*i] (and its value); 0, or 2 when it is not an option or lacks its value. */
static int read_option(int argc, char **argv, int *i, track_options_t *o)
{
    const char *value;
    const option_t *option = find_option(argv[*i], &value);
    if (strcmp(argv[*i], "--seconds") == 0 || strncmp(argv[*i], "--seconds=", 10) == 0) {
        const char *text = argv[*i][9] == '=' ? argv[*i] + 10 : (*i + 1 < argc ? argv[++*i] : NULL);
        if (text == NULL || !argument_number(text, 0.0, 1e9, &o->seconds)) {
            return bad("--seconds wants a duration >= 0, not ", text != NULL ? text : "nothing");
        }
        return 0;
    }
    if (option == NULL) return bad("unknown option ", argv[*i]);
    if (option->kind == OPTION_FLAG) {
        if (value != NULL) return bad(option->name, " takes no value");
        *(int *)((char *)o + option->offset) = 1;
        return 0;
    }
    if (value == NULL) {
        if (*i + 1 >= argc) return bad(option->name, " wants a value");
        value = argv[++*i];
    }
    *(const char **)((char *)o + option->offset) = value;
    return 0;
}

/* The rules between options: one source, a source that exists, a known detector, a rate in range. */
static int check(const track_options_t *o)
{
    struct stat info;
    double rate;
    long port;
    char host[64], reason[256];
    unsigned view_port;
    if ((o->camera == NULL) == (o->source == NULL)) return bad("give one of --camera N and --source FILE", NULL);
    if (o->source != NULL && stat(o->source, &info) != 0) {
        return bad("--source: no such file or folder: ", o->source);
    }
    if (o->detector != NULL && strcmp(o->detector, "retina") != 0 && strcmp(o->detector, "short") != 0 &&
        strcmp(o->detector, "full") != 0) {
        return bad("--detector wants retina, short or full, not ", o->detector);
    }
    if (o->stillness != NULL && (strlen(o->stillness) > 32 || !argument_number(o->stillness, 0.0, 100.0, &rate))) { /* libhkf's HKF_MAX_STILLNESS */
        return bad("--stillness wants a multiple of the measured wander from 0 to 100, not ", o->stillness);
    }
    if (o->rate != NULL && !argument_number(o->rate, 0.1, 10000.0, &rate)) { /* hkf-filter's range */
        return bad("--rate wants a frequency from 0.1 to 10000 Hz, not ", o->rate);
    }
    if (!argument_port(o->opentrack_port, 1, &port)) {
        return bad("--opentrack-port wants a UDP port from 1 to 65535 (digits alone), not ", o->opentrack_port);
    }
    if (o->flightgear != NULL && !argument_port(o->flightgear_port, 1, &port)) {
        return bad("--flightgear wants [HOST:]PORT, a UDP port from 1 to 65535 (digits alone), not ", o->flightgear);
    }
    if (o->view != NULL && view_listen_parse(o->view, host, sizeof host, &view_port, reason, sizeof reason) != 0) {
        return bad("--view: ", reason);
    }
    if (strncmp(o->lcm_url, "file://", 7) == 0) {
        return bad("--lcm-url: hkf-track runs live programs; a file:// log is for hkf-estimator and "
                   "hkf-filter --offline, not ", o->lcm_url);
    }
    if (strncmp(o->lcm_url, "memq://", 7) == 0) { /* each program would have a queue of its own */
        return bad("--lcm-url: memq:// stays inside one process; hkf-track's programs are separate processes "
                   "and need a network provider (udpm://), not ", o->lcm_url);
    }
    return 0;
}

/* --flightgear's [HOST:]PORT into flightgear_host and flightgear_port (the port checked with the rest). 0, or
 * 2 (said) when the host does not fit. */
static int split_flightgear(track_options_t *o)
{
    const char *colon = o->flightgear != NULL ? strrchr(o->flightgear, ':') : NULL;
    size_t length = colon != NULL ? (size_t)(colon - o->flightgear) : 0;
    if (o->flightgear == NULL) return 0;
    if (length >= sizeof o->flightgear_host) return bad("--flightgear: the host is too long: ", o->flightgear);
    memcpy(o->flightgear_host, o->flightgear, length);
    o->flightgear_host[length] = '\0';
    if (length == 0) strcpy(o->flightgear_host, "127.0.0.1");
    o->flightgear_port = colon != NULL ? colon + 1 : o->flightgear;
    return 0;
}

int track_options_parse(int argc, char **argv, track_options_t *o)
{
    memset(o, 0, sizeof *o);
    o->opentrack_host = "127.0.0.1";
    o->opentrack_port = "4242";
    o->opentrack_args = "";
    o->flightgear_args = "";
    o->lcm_url = LCM_URL_DEFAULT;
    o->logs = "hkf-track-logs";
    for (int i = 1; i < argc; ++i) {
        if (argument_help_or_version(argv[i], "hkf-track", usage)) return 1;
        int status = read_option(argc, argv, &i, o);
        if (status != 0) return status;
    }
    o->lcm_url = lcm_url_resolve(o->lcm_url); /* '': $LCM_DEFAULT_URL, as LCM reads it; passed on resolved */
    return split_flightgear(o) != 0 ? 2 : check(o);
}
