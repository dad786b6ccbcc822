/*
 * hkf-opentrack - the bridge to opentrack: subscribes the filtered head pose
 * (HEAD_POSE) and sends each one to opentrack's "UDP over network" input as
 * one datagram (opentrack_packet.h has the format and the angle mapping).
 * opentrack then moves the camera of every game it supports. With --flightgear
 * the same poses, by the same rules, go to FlightGear's generic input as one
 * line each (flightgear_line.h), which moves FlightGear's cockpit view.
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <netdb.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include <lcm/lcm.h>

#include "arguments.h"
#include "clocks.h"
#include "flightgear_line.h"

#include "lcm_file_url.h"
#include "lcm_wait.h"
#include "message_decode.h"
#include "opentrack_packet.h"


typedef enum { LOST_HOLD, LOST_CENTER, LOST_SEND } lost_policy_t;

typedef struct {
    const char *lcm_url, *channel, *host, *port;
    long bind_port;       /* local source port, 0 = any */
    double rate_hz;       /* 0: one datagram per pose */
    int predict;          /* --predict: each datagram shows the pose moved on to when it is sent */
    double lead_s;        /* --lead: and this much further */
    lost_policy_t lost;
    opentrack_mapping_t mapping;
    int flightgear;       /* --flightgear: FlightGear's generic input, one line a pose */
    double eye[3];        /* --eye: the aircraft's eye point (m), added to the head's offset for FlightGear */
    const char *target;   /* "opentrack" or "FlightGear", for the messages */
} options_t;

typedef struct {
    unsigned long received, sent, held, centered, non_finite, absurd, send_errors, decode_errors, position_beyond;
    unsigned long unknown_status; /* poses of a status hkf-filter never publishes: corrupt */
} bridge_counts_t;

typedef struct {
    const options_t *options;
    int socket_fd;
    unsigned char packet[FLIGHTGEAR_LINE_MAX]; /* the latest packet: what --rate repeats, LOST holds */
    size_t packet_size;                        /* OPENTRACK_PACKET_SIZE, or the FlightGear line's length */
    int have_packet;
    double last_values[OPENTRACK_FIELDS]; /* the last pose's values: a position beyond the range keeps its */
    hkf_head_pose_t pose;                 /* the last pose taken, which --predict moves on at each send */
    int have_pose;
    bridge_counts_t counts;
} bridge_t;

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

static int parse_port(const char *text, long low, long *port)
{
    char *end = NULL;
    errno = 0;
    *port = strtol(text, &end, 10);
    return end != text && *end == '\0' && errno == 0 && *port >= low && *port <= 65535 ? 0 : -1;
}

/* --invert, --scale or --lost with its value: 0, -1 when arg is none of them, 2 for a bad value (said). */
static int mapping_option(options_t *o, const char *arg, const char *value)
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
static int number_option(options_t *o, const char *arg, const char *value)
{
    long port;
    if (strcmp(arg, "--port") == 0 || strcmp(arg, "--bind") == 0) {
        const int bind = strcmp(arg, "--bind") == 0;
        if (parse_port(value, 1, bind ? &o->bind_port : &port) != 0) {
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
static int value_option(options_t *o, const char *arg, const char *value)
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

/* 0 = run, 1 = done (help), 2 = bad arguments */
static int parse_options(int argc, char **argv, options_t *o)
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

/* A UDP socket connected to host:port (so a refusing destination shows as an
 * error on the next send), bound to --bind if given. -1 after a message. */
static int open_socket(const options_t *o)
{
    struct addrinfo hints, *found = NULL, *a;
    int fd = -1, result;
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_DGRAM;
    result = getaddrinfo(o->host, o->port, &hints, &found);
    if (result != 0) {
        fprintf(stderr, "hkf-opentrack: cannot resolve the host '%s': %s\n", o->host, gai_strerror(result));
        return -1;
    }
    for (a = found; a != NULL && fd < 0; a = a->ai_next) {
        fd = socket(a->ai_family, a->ai_socktype, a->ai_protocol);
        if (fd < 0) {
            continue;
        }
        if (o->bind_port > 0) {
            struct sockaddr_storage local;
            socklen_t length;
            memset(&local, 0, sizeof local);
            if (a->ai_family == AF_INET6) {
                struct sockaddr_in6 *in6 = (struct sockaddr_in6 *)&local;
                in6->sin6_family = AF_INET6;
                in6->sin6_port = htons((unsigned short)o->bind_port);
                in6->sin6_addr = in6addr_any;
                length = sizeof *in6;
            } else {
                struct sockaddr_in *in4 = (struct sockaddr_in *)&local;
                in4->sin_family = AF_INET;
                in4->sin_port = htons((unsigned short)o->bind_port);
                in4->sin_addr.s_addr = htonl(INADDR_ANY);
                length = sizeof *in4;
            }
            if (bind(fd, (struct sockaddr *)&local, length) != 0) {
                fprintf(stderr, "hkf-opentrack: cannot send from local UDP port %ld: %s\n", o->bind_port,
                        errno == EADDRINUSE ? "the port is in use by another program" : strerror(errno));
                close(fd);
                freeaddrinfo(found);
                return -1;
            }
        }
        if (connect(fd, a->ai_addr, a->ai_addrlen) != 0) {
            fprintf(stderr, "hkf-opentrack: cannot reach %s port %s: %s\n", o->host, o->port, strerror(errno));
            close(fd);
            fd = -1;
        }
    }
    freeaddrinfo(found);
    if (fd < 0) {
        fprintf(stderr, "hkf-opentrack: no usable address for %s port %s\n", o->host, o->port);
    }
    return fd;
}

static void send_packet(bridge_t *bridge)
{
    const options_t *o = bridge->options;
    if (send(bridge->socket_fd, bridge->packet, bridge->packet_size, MSG_DONTWAIT) == (ssize_t)bridge->packet_size) {
        ++bridge->counts.sent;
        return;
    }
    /* opentrack or FlightGear not (yet) listening, a full buffer, a network down: the next pose tries again */
    if (bridge->counts.send_errors++ < 5) {
        fprintf(stderr, "hkf-opentrack: sending to %s port %s failed: %s%s\n", o->host, o->port, strerror(errno),
                errno != ECONNREFUSED ? ""
                : o->flightgear      ? " (is FlightGear running with --generic=socket,in,...,udp,hkf?)"
                                     : " (is opentrack running with the \"UDP over network\" input?)");
    }
}

/* The six values as the packet (opentrack's datagram, or FlightGear's line): 0, or -1 when FlightGear's
 * line cannot be made (a value not finite: never sent). */
static int encode(bridge_t *bridge, const double values[OPENTRACK_FIELDS])
{
    double view[6];
    int length;
    if (!bridge->options->flightgear) {
        opentrack_encode(values, bridge->packet);
        bridge->packet_size = OPENTRACK_PACKET_SIZE;
        return 0;
    }
    flightgear_view_values(values, bridge->options->eye, view);
    length = flightgear_line(view, (char *)bridge->packet, sizeof bridge->packet);
    bridge->packet_size = length > 0 ? (size_t)length : 0;
    return length > 0 ? 0 : -1;
}

/* A tracked or coasting pose into the packet (moved on to now with --predict); 0, or -1 when
 * it is not sent (counted: non-finite, or beyond +-180 deg). `count`: a new pose, not a tick's
 * repeat (--rate --predict), so its problems are counted once. */
static int pack_pose(bridge_t *bridge, const hkf_head_pose_t *pose, int count)
{
    const options_t *o = bridge->options;
    const hkf_head_pose_t sent =
        o->predict ? opentrack_predict(pose, opentrack_horizon(pose, clock_wall_us(), o->lead_s)) : *pose;
    double values[OPENTRACK_FIELDS];
    int result;
    memcpy(values, bridge->last_values, sizeof values); /* the last position, should this one be beyond */
    result = opentrack_pose_values(&o->mapping, &sent, values);
    if (result == -4) {
        if (count && bridge->counts.unknown_status++ < 5) {
            fprintf(stderr, "hkf-opentrack: a pose of unknown status %d not sent: corrupt\n", (int)pose->status);
        }
        return -1;
    }
    if (result == -1 || result == -2) {
        if (count && result == -2 && bridge->counts.absurd++ < 5) {
            fprintf(stderr, "hkf-opentrack: a pose beyond +-180 deg (pitch %g, yaw %g, roll %g) not sent: forged "
                            "or corrupt\n", (double)pose->pitch, (double)pose->yaw, (double)pose->roll);
        }
        bridge->counts.non_finite += count && result == -1;
        return -1;
    }
    if (count && result == -3 && bridge->counts.position_beyond++ < 5) {
        fprintf(stderr, "hkf-opentrack: a position not finite or beyond +-1000 cm (x %g, y %g, z %g) not sent: the "
                        "angles went with the last position\n", (double)pose->x, (double)pose->y, (double)pose->z);
    }
    if (encode(bridge, values) != 0) {
        bridge->counts.non_finite += count;
        return -1;
    }
    memcpy(bridge->last_values, values, sizeof values);
    bridge->have_packet = 1;
    return 0;
}

/* One pose -> the packet to send (or none); then sent unless --rate sends it. 0, or -1 when it is
 * not sent: then --rate sends nothing until a pose is (the last packet is no longer the head's), as
 * without --rate, and opentrack holds the camera where it was. */
static int handle_pose(bridge_t *bridge, const hkf_head_pose_t *pose)
{
    const options_t *o = bridge->options;
    ++bridge->counts.received;
    if (pose->status == HKF_HEAD_POSE_T_LOST && o->lost == LOST_HOLD) {
        if (!bridge->have_packet) {
            return 0; /* nothing to hold yet */
        }
        ++bridge->counts.held;
    } else if (pose->status == HKF_HEAD_POSE_T_LOST && o->lost == LOST_CENTER) {
        const double centre[OPENTRACK_FIELDS] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
        bridge->have_packet = encode(bridge, centre) == 0;
        ++bridge->counts.centered;
    } else if (pack_pose(bridge, pose, 1) != 0) {
        bridge->have_packet = 0;
        return -1;
    }
    if (o->rate_hz <= 0.0) {
        send_packet(bridge);
    }
    return 0;
}

/* --rate with --predict: the last pose moved on to this tick (a LOST pose stays as it was sent). */
static void repredict(bridge_t *bridge)
{
    if (bridge->have_pose && bridge->pose.status != HKF_HEAD_POSE_T_LOST) {
        (void)pack_pose(bridge, &bridge->pose, 0);
    }
}

static void on_pose(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    bridge_t *bridge = user;
    hkf_head_pose_t pose;
    if (message_decode_pose(rbuf->data, (int)rbuf->data_size, &pose) != 0) {
        if (bridge->counts.decode_errors++ < 5) {
            fprintf(stderr, "hkf-opentrack: a message on %s did not decode; counted and skipped\n", channel);
        }
        return;
    }
    bridge->have_pose = handle_pose(bridge, &pose) == 0; /* --predict moves on only a pose that was sent */
    bridge->pose = pose;
    hkf_head_pose_t_decode_cleanup(&pose);
}

static int run(bridge_t *bridge)
{
    const options_t *o = bridge->options;
    lcm_file_url_t log_file;
    lcm_t *lcm;
    const int64_t tick_us = o->rate_hz > 0.0 ? (int64_t)(1e6 / o->rate_hz) : 0;
    int64_t next_tick = clock_monotonic_us() + tick_us;
    int status = 0;
    if (lcm_file_url_check(o->lcm_url, "input", NULL, 0, "hkf-opentrack", &log_file) != 0) {
        return 1; /* a file:// URL: a regular log, read; a named pipe would hang LCM */
    }
    lcm = lcm_create(lcm_url_resolve(o->lcm_url)); /* '': $LCM_DEFAULT_URL, as checked */
    if (lcm == NULL) {
        fprintf(stderr, "hkf-opentrack: cannot open LCM provider '%s'\n", o->lcm_url);
        return 1;
    }
    if (lcm_wait_subscribe(lcm, o->channel, on_pose, bridge, "hkf-opentrack") == NULL) {
        lcm_destroy(lcm);
        return 1;
    }
    lcm_wait_stop_on_signals();
    fprintf(stderr, "hkf-opentrack: %s on %s -> %s at %s port %s\n", o->channel, o->lcm_url, o->target, o->host, o->port);
    while (!lcm_wait_stop_requested()) {
        if (lcm_wait_and_handle(lcm, lcm_wait_time(tick_us > 0 ? next_tick : 0, clock_monotonic_us()), "hkf-opentrack") < 0) {
            status = 1;
            break;
        }
        if (tick_us > 0 && clock_monotonic_us() >= next_tick) {
            if (o->predict) {
                repredict(bridge);
            }
            if (bridge->have_packet) {
                send_packet(bridge);
            }
            next_tick += tick_us;
            if (next_tick < clock_monotonic_us()) {
                next_tick = clock_monotonic_us() + tick_us; /* fell behind: no burst to catch up */
            }
        }
    }
    lcm_destroy(lcm);
    return status;
}

int main(int argc, char **argv)
{
    static options_t options;
    static bridge_t bridge;
    const bridge_counts_t *c = &bridge.counts;
    int status;
    switch (parse_options(argc, argv, &options)) {
    case 1: return 0;
    case 2: return 2;
    default: break;
    }
    bridge.options = &options;
    bridge.socket_fd = open_socket(&options);
    if (bridge.socket_fd < 0) {
        return 1;
    }
    status = run(&bridge);
    close(bridge.socket_fd);
    fprintf(stderr,
            "hkf-opentrack: %lu poses received, %lu datagrams sent to %s at %s port %s (%lu repeats of the last pose "
            "while LOST, %lu centre poses while LOST); dropped: %lu non-finite, %lu beyond +-180 deg, %lu send "
            "errors, %lu undecodable, %lu of unknown status; %lu positions beyond +-1000 cm held at the last\n",
            c->received, c->sent, options.target, options.host, options.port, c->held, c->centered, c->non_finite, c->absurd,
            c->send_errors, c->decode_errors, c->unknown_status, c->position_beyond);
    return status;
}
