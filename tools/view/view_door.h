/*
 * view_door.h - who may use the live view (hkf-view): the page controls the tracker, so every request is
 * checked as at a door. A request is served only when
 * - its Host names the view itself: the address it listens on, or, where that is a loopback or every
 *   address, localhost or an address literal, with the view's port (a DNS name that rebinds to this host
 *   names neither);
 * - its Origin, if it has one, is http:// and such a Host (no other site's page may read or command it);
 * - its Sec-Fetch-Site, if the browser sends one, says the page's own or the user's (an <img> on another site
 *   sends no Origin, but says cross-site here: it may not show the camera's picture);
 * - for a command, it carries the run's token, which only the served page has;
 * - it asks for one of the page's own assets, by exact name.
 * Pure functions over the request's text: no sockets, so each rule is tested alone.
 */
#ifndef VIEW_DOOR_H
#define VIEW_DOOR_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define VIEW_TOKEN_CHARS 32 /* 128 random bits, hex */

typedef struct {
    char address[64];  /* the address listened on: 127.0.0.1 (default), 0.0.0.0, or another IPv4 literal */
    unsigned port;
    char token[VIEW_TOKEN_CHARS + 1];
} view_door_t;

/* The door for address:port with a fresh token from the system's random source. 0, or -1 when no random
 * bytes could be had (said on stderr) or the address is not an IPv4 literal. */
int view_door_open(view_door_t *door, const char *address, unsigned port);

/* 1 when host (the Host header's value, NULL when missing) names the view; 0 otherwise. */
int view_door_host_ok(const view_door_t *door, const char *host);

/* 1 when origin (NULL: the request has none, as a page's own GET) is the view's own; 0 otherwise. */
int view_door_origin_ok(const view_door_t *door, const char *origin);

/* 1 when site (the Sec-Fetch-Site header, NULL: none, as from curl or an older browser) is "same-origin" or
 * "none" (typed into the address bar); 0 for "same-site", "cross-site" or anything else. */
int view_door_fetch_site_ok(const char *site);

/* 1 when given (NULL when missing) is the run's token, compared in constant time; 0 otherwise. */
int view_door_token_ok(const view_door_t *door, const char *given);

#ifdef __cplusplus
}
#endif

#endif /* VIEW_DOOR_H */
