/* view_door.c - see view_door.h. */
#define _POSIX_C_SOURCE 200809L

#include "view_door.h"

#include <arpa/inet.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int random_bytes(unsigned char *out, size_t n)
{
    FILE *f = fopen("/dev/urandom", "rb");
    size_t got;
    if (f == NULL) {
        return -1;
    }
    got = fread(out, 1, n, f);
    return fclose(f) == 0 && got == n ? 0 : -1;
}

int view_door_open(view_door_t *door, const char *address, unsigned port)
{
    unsigned char bits[VIEW_TOKEN_CHARS / 2];
    struct in_addr parsed;
    size_t i;
    memset(door, 0, sizeof *door);
    if (strlen(address) >= sizeof door->address || inet_pton(AF_INET, address, &parsed) != 1) {
        fprintf(stderr, "hkf-view: '%s' is not an IPv4 address to listen on (e.g. 127.0.0.1 or 0.0.0.0)\n", address);
        return -1;
    }
    if (random_bytes(bits, sizeof bits) != 0) {
        fprintf(stderr, "hkf-view: no random bytes for the commands' token (/dev/urandom)\n");
        return -1;
    }
    strcpy(door->address, address);
    door->port = port;
    for (i = 0; i < sizeof bits; ++i) {
        snprintf(door->token + 2 * i, 3, "%02x", bits[i]);
    }
    return 0;
}

static int is_loopback_or_any(const char *address)
{
    return strncmp(address, "127.", 4) == 0 || strcmp(address, "0.0.0.0") == 0;
}

/* 1 when name (a host without its port) may name this view. */
static int name_ok(const view_door_t *door, const char *name, size_t length)
{
    char text[64];
    struct in_addr parsed;
    if (length == 0 || length >= sizeof text) {
        return 0;
    }
    memcpy(text, name, length);
    text[length] = '\0';
    if (strcmp(text, door->address) == 0) {
        return 1;
    }
    if (!is_loopback_or_any(door->address)) {
        return 0; /* bound to one address: only that one */
    }
    if (strcmp(text, "localhost") == 0 || strcmp(text, "[::1]") == 0) {
        return 1;
    }
    /* bound to loopback: any loopback literal; bound to every address: any address literal of this host */
    return inet_pton(AF_INET, text, &parsed) == 1 &&
           (strcmp(door->address, "0.0.0.0") == 0 || strncmp(text, "127.", 4) == 0);
}

int view_door_host_ok(const view_door_t *door, const char *host)
{
    const char *colon;
    char *end;
    unsigned long port;
    if (host == NULL) {
        return 0;
    }
    colon = strrchr(host, ':');
    if (colon == NULL || colon[1] < '0' || colon[1] > '9') {
        return 0; /* the view's port is never 80: a Host without it names something else */
    }
    port = strtoul(colon + 1, &end, 10);
    return *end == '\0' && port == door->port && name_ok(door, host, (size_t)(colon - host));
}

int view_door_origin_ok(const view_door_t *door, const char *origin)
{
    if (origin == NULL) {
        return 1;
    }
    return strncmp(origin, "http://", 7) == 0 && view_door_host_ok(door, origin + 7);
}

int view_door_fetch_site_ok(const char *site)
{
    return site == NULL || strcmp(site, "same-origin") == 0 || strcmp(site, "none") == 0;
}

int view_door_token_ok(const view_door_t *door, const char *given)
{
    unsigned char differ = 0;
    size_t i;
    if (given == NULL || strlen(given) != VIEW_TOKEN_CHARS) {
        return 0;
    }
    for (i = 0; i < VIEW_TOKEN_CHARS; ++i) {
        differ |= (unsigned char)(given[i] ^ door->token[i]);
    }
    return differ == 0;
}
