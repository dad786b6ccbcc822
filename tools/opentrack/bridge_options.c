/* bridge_options.c - see bridge_options.h. */
#define _POSIX_C_SOURCE 200809L

#include "bridge_options.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lcm/lcm.h>

#include "arguments.h"
#include "flightgear_line.h"
#include "lcm_file_url.h"

static void usage(FILE *to)
{
    fprintf(to,
            "usage: hkf-opentrack [options]\n"
            "Sends every filtered head pose (hkf.head_pose_t) to opentrack's \"UDP over network\"\n"
            "input: one datagram of six little-endian doubles x, y, z (cm: hkf's head position, x right,\n"
            "y up, z away from the camera), yaw, pitch, roll (deg), roll's sign flipped to opentrack's\n"
            "convention.\n"
            "  --lcm-url URL      LCM provider (default " LCM_URL_DEFAULT ")\n"
            "  --channel C        filtered poses (default HEAD_POSE)\n"
            "  --host H           opentrack's address (default 127.0.0.1)\n"
            "  --port P           opentrack's UDP port (default 4242)\n"
            "  --bind P           send from this local UDP port (default: any free one)\n"
            "  --absolute         send the absolute pose; by default the pose minus hkf's centre pose\n"
            "                     and centre position, so 'hkf-cmd recenter' re-zeroes the game camera\n"
            "  --invert AXIS      flip yaw, pitch, roll, x, y or z (repeatable, or a list: yaw,z)\n"
            "  --scale AXIS=K     multiply yaw, pitch, roll, x, y or z by K (repeatable), e.g. --scale yaw=1.5\n"
            "  --lost hold|center|send\n"
            "                     while the face is LOST: repeat the last pose sent (hold, default),\n"
            "                     send the centre (0, 0, 0), or send the filter's held pose as is\n"
            "  --rate HZ          send the latest pose at this fixed rate (1 to 1000) instead of once per pose\n"
            "                     (run hkf-filter --rate too, for extrapolated poses in between)\n"
            "  --predict          send each pose moved on by its rates to the moment it is sent (when its\n"
            "                     capture stamp is on this machine's clock and at most 250 ms old)\n"
            "  --lead MS          with --predict, this much further ahead (0 to 100 ms): the camera's own\n"
            "                     delay before the capture stamp\n"
            "  --flightgear       send to FlightGear's generic input instead (default port 5550): one line\n"
            "                     a pose, heading, pitch, roll (deg), x, y, z (m) of the view, for the protocol\n"
            "                     file hkf.xml (/usr/share/hkf/flightgear/Protocol/); run fgfs with\n"
            "                     --data=/usr/share/hkf/flightgear --generic=socket,in,60,,5550,udp,hkf\n"
            "  --eye X,Y,Z        with --flightgear, the aircraft's eye point (m; its view's x/y/z-offset-m),\n"
            "                     which the head's offset is added to (default 0,0,0)\n"
            "  --help, --version  this text; the version\n"
            "Non-finite poses, and angles beyond +-180 deg that no head makes (a forged or corrupt\n"
            "message), are never sent (counted); a destination that refuses (opentrack not running) is\n"
            "counted and retried with the next pose. Stops on SIGINT / SIGTERM / SIGHUP with a summary.\n");
}

static int parse_invert(const char *list, opentrack_mapping_t *mapping)
{
    char buffer[64];
    char *token, *rest;
    if (strlen(list) >= sizeof buffer) {
        return -1;
    }
    strcpy(buffer, list);
    for (token = strtok_r(buffer, ",", &rest); token != NULL; token = strtok_r(NULL, ",", &rest)) {
        const int axis = opentrack_axis_from_name(token);
        if (axis < 0) {
            return -1;
        }
        mapping->invert[axis] = 1;
    }
    return 0;
}

static int parse_scale(const char *text, opentrack_mapping_t *mapping)
{
    char name[16];
    const char *equals = strchr(text, '=');
    char *end = NULL;
    double k;
    int axis;
    if (equals == NULL || equals - text >= (long)sizeof name) {
        return -1;
    }
    memcpy(name, text, (size_t)(equals - text));
    name[equals - text] = '\0';
    axis = opentrack_axis_from_name(name);
    errno = 0;
    k = strtod(equals + 1, &end);
    if (axis < 0 || end == equals + 1 || *end != '\0' || errno != 0 || !(k >= -100.0 && k <= 100.0)) {
        return -1;
    }
    mapping->scale[axis] = k;
    return 0;
}

/* --invert, --scale or --lost with its value: 0, -1 when arg is none of them, 2 for a bad value (said). */
static int mapping_option(bridge_options_t *o, const char *arg, const char *value)
{
    static const char *const lost_names[] = {"hold", "center", "send"}; /* lost_policy_t's order */
    if (strcmp(arg, "--invert") == 0) {
        if (parse_invert(value, &o->mapping) == 0) return 0;
        fprintf(stderr, "hkf-opentrack: --invert wants yaw, pitch, roll, x, y or z (or a list), not '%s'\n", value);
        return 2;
    }
    if (strcmp(arg, "--scale") == 0) {
        if (parse_scale(value, &o->mapping) == 0) return 0;
        fprintf(stderr, "hkf-opentrack: --scale wants AXIS=K (yaw, pitch, roll, x, y or z; K from -100 to 100), "
                        "not '%s'\n", value);
        return 2;
    }
    if (strcmp(arg, "--lost") == 0) {
        for (int k = 0; k < 3; ++k) {
            if (strcmp(value, lost_names[k]) == 0) {
                o->lost = (lost_policy_t)k;
                return 0;
            }
        }
        fprintf(stderr, "hkf-opentrack: --lost wants hold, center or send, not '%s'\n", value);
        return 2;
    }
    return -1;
}

/* --eye's X,Y,Z (m, each within +-100): 0, or -1. */
static int parse_eye(const char *text, double eye[3])
{
    char rest;
    return sscanf(text, "%lf,%lf,%lf%c", &eye[0], &eye[1], &eye[2], &rest) == 3 && fabs(eye[0]) <= 100.0 &&
                   fabs(eye[1]) <= 100.0 && fabs(eye[2]) <= 100.0
               ? 0
               : -1;
}

/* --port, --bind, --lead or --rate with its value: 0, -1 when arg is none of them, 2 for a bad value (said). */
static int number_option(bridge_options_t *o, const char *arg, const char *value)
{
    long port;
    if (strcmp(arg, "--port") == 0 || strcmp(arg, "--bind") == 0) {
        const int bind = strcmp(arg, "--bind") == 0;
        if (!argument_port(value, 1, bind ? &o->bind_port : &port)) {
            fprintf(stderr, "hkf-opentrack: %s wants a UDP port from 1 to 65535, not '%s'\n", arg, value);
            return 2;
        }
        o->port = bind ? o->port : value;
        return 0;
    }
    if (strcmp(arg, "--lead") == 0) {
        if (!argument_number(value, 0.0, 100.0, &o->lead_s)) {
            fprintf(stderr, "hkf-opentrack: --lead wants milliseconds from 0 to 100, not '%s'\n", value);
            return 2;
        }
        o->lead_s *= 1e-3;
        o->predict = 1;
        return 0;
    }
    if (strcmp(arg, "--rate") == 0) {
        if (argument_number(value, 1.0, 1000.0, &o->rate_hz)) return 0;
        fprintf(stderr, "hkf-opentrack: --rate wants a frequency from 1 to 1000 Hz, not '%s'\n", value);
        return 2;
    }
    return -1;
}

/* An option with a value: 0, 2 for a bad or unknown one (said). */
static int value_option(bridge_options_t *o, const char *arg, const char *value)
{
    int result;
    if (strcmp(arg, "--lcm-url") == 0) {
        o->lcm_url = value;
    } else if (strcmp(arg, "--channel") == 0) {
        o->channel = value;
    } else if (strcmp(arg, "--host") == 0) {
        o->host = value;
    } else if (strcmp(arg, "--eye") == 0) {
        if (parse_eye(value, o->eye) != 0) {
            fprintf(stderr, "hkf-opentrack: --eye wants X,Y,Z in m (each within +-100), not '%s'\n", value);
            return 2;
        }
    } else if ((result = number_option(o, arg, value)) >= 0 || (result = mapping_option(o, arg, value)) >= 0) {
        return result;
    } else {
        fprintf(stderr, "hkf-opentrack: unknown or incomplete argument '%s' (see --help)\n", arg);
        return 2;
    }
    return 0;
}

int bridge_options_parse(int argc, char **argv, bridge_options_t *o)
{
    memset(o, 0, sizeof *o);
    o->lcm_url = LCM_URL_DEFAULT;
    o->channel = "HEAD_POSE";
    o->host = "127.0.0.1";
    o->port = NULL; /* 4242, or 5550 with --flightgear */
    o->lost = LOST_HOLD;
    o->mapping = opentrack_default_mapping();
    for (int i = 1; i < argc; ++i) {
        const char *arg = argv[i];
        const char *value = i + 1 < argc ? argv[i + 1] : NULL;
        if (argument_help_or_version(arg, "hkf-opentrack", usage)) {
            return 1;
        } else if (strcmp(arg, "--absolute") == 0) {
            o->mapping.relative_to_center = 0;
        } else if (strcmp(arg, "--predict") == 0) {
            o->predict = 1;
        } else if (strcmp(arg, "--flightgear") == 0) {
            o->flightgear = 1;
        } else if (value == NULL) {
            fprintf(stderr, "hkf-opentrack: unknown or incomplete argument '%s' (see --help)\n", arg);
            return 2;
        } else if (value_option(o, arg, argv[++i]) != 0) {
            return 2;
        }
    }
    o->target = o->flightgear ? "FlightGear" : "opentrack";
    if (o->port == NULL) {
        o->port = o->flightgear ? FLIGHTGEAR_DEFAULT_PORT : "4242";
    }
    if (o->channel[0] == '\0' || strlen(o->channel) > LCM_MAX_CHANNEL_NAME_LENGTH) {
        fprintf(stderr, "hkf-opentrack: a channel name has 1 to %d characters, not '%.80s'\n",
                LCM_MAX_CHANNEL_NAME_LENGTH, o->channel);
        return 2;
    }
    return 0;
}
