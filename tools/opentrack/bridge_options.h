/*
 * bridge_options.h - hkf-opentrack's command line: where the poses come from and go (opentrack's UDP input,
 * or FlightGear's generic input with --flightgear), the mapping (--absolute, --invert, --scale), --lost,
 * --rate, --predict and --lead.
 */
#ifndef BRIDGE_OPTIONS_H
#define BRIDGE_OPTIONS_H

#include "opentrack_packet.h"

#ifdef __cplusplus
extern "C" {
#endif

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
} bridge_options_t;

/* Reads the command line into *o: 0 = run, 1 = done (--help or --version answered), 2 = bad arguments (said). */
int bridge_options_parse(int argc, char **argv, bridge_options_t *o);

#ifdef __cplusplus
}
#endif

#endif /* BRIDGE_OPTIONS_H */
