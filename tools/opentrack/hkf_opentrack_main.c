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
#include <netdb.h>
#include <netinet/in.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include <lcm/lcm.h>

#include "bridge_options.h"
#include "clocks.h"
#include "flightgear_line.h"

#include "lcm_file_url.h"
#include "lcm_wait.h"
#include "message_decode.h"
#include "opentrack_packet.h"

typedef struct {
    unsigned long received, sent, held, centered, non_finite, absurd, send_errors, decode_errors, position_beyond;
    unsigned long unknown_status; /* poses of a status hkf-filter never publishes: corrupt */
} bridge_counts_t;

typedef struct {
    const bridge_options_t *options;
    int socket_fd;
    unsigned char packet[FLIGHTGEAR_LINE_MAX]; /* the latest packet: what --rate repeats, LOST holds */
    size_t packet_size;                        /* OPENTRACK_PACKET_SIZE, or the FlightGear line's length */
    int have_packet;
    double last_values[OPENTRACK_FIELDS]; /* the last pose's values: a position beyond the range keeps its */
    hkf_head_pose_t pose;                 /* the last pose taken, which --predict moves on at each send */
    int have_pose;
    bridge_counts_t counts;
} bridge_t;

/* A UDP socket connected to host:port (so a refusing destination shows as an
 * error on the next send), bound to --bind if given. -1 after a message. */
static int open_socket(const bridge_options_t *o)
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
    const bridge_options_t *o = bridge->options;
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
    const bridge_options_t *o = bridge->options;
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
    const bridge_options_t *o = bridge->options;
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
    const bridge_options_t *o = bridge->options;
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
    static bridge_options_t options;
    static bridge_t bridge;
    const bridge_counts_t *c = &bridge.counts;
    int status;
    switch (bridge_options_parse(argc, argv, &options)) {
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
