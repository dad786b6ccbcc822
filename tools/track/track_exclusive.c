/* track_exclusive.c - see track_exclusive.h. */
#define _GNU_SOURCE /* flock's LOCK_* names with c99 */

#include "track_exclusive.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

/* What LCM will use of url, as a key: for udpm, the multicast group (inet_aton) and port (strtol, base 0,
 * trailing text ignored) as LCM 1.4 reads them, with LCM's
 * defaults filled in (239.255.76.67, 7667), so that "udpm://239.255.76.67:7667?ttl=0" and
 * "udpm://239.255.76.67:7667" are one key. The TTL is left out on purpose: two trackers on one group and
 * port receive each other's poses whatever TTL each sends with. Any other provider: its text. */
static void url_key(const char *url, char *key, size_t size)
{
    static const char udpm[] = "udpm://";
    char address[64] = "239.255.76.67";
    unsigned long port = 7667;
    struct in_addr group;
    const char *network = url + sizeof udpm - 1, *colon, *end;
    size_t length;
    if (strncmp(url, udpm, sizeof udpm - 1) != 0) {
        snprintf(key, size, "%s", url);
        return;
    }
    end = network + strcspn(network, "?");
    colon = memchr(network, ':', (size_t)(end - network));
    length = (size_t)((colon != NULL ? colon : end) - network);
    if (length > 0) {
        if (length >= sizeof address) {
            snprintf(key, size, "%s", url);
            return;
        }
        memcpy(address, network, length);
        address[length] = '\0';
    }
    if (colon != NULL) { /* as LCM reads it: strtol(..., 0), so 0x1df3, 017763, " +7667" and 7667abc are 7667 */
        char *stop;
        const long read = strtol(colon + 1, &stop, 0);
        if (stop == colon + 1 || read < 0 || read > 65535) {
            snprintf(key, size, "%s", url); /* LCM refuses it: keyed on its text */
            return;
        }
        port = (unsigned long)read;
    }
    if (inet_aton(address, &group) == 0) { /* as LCM reads it (an octal 076 is 62) */
        snprintf(key, size, "%s", url);
        return;
    }
    snprintf(key, size, "udpm %s %lu", inet_ntoa(group), port);
}

/* The 64-bit FNV-1a hash of text: a key too long for a socket's name is named by it, never cut. */
static unsigned long long fnv1a(const char *text)
{
    unsigned long long hash = 14695981039346656037ULL;
    for (; *text != '\0'; ++text) {
        hash = (hash ^ (unsigned char)*text) * 1099511628211ULL;
    }
    return hash;
}

/* Binds the abstract socket "\0hkf-track KEY" (url_key), or "\0hkf-track #HASH" for a key too long for
 * sun_path. The socket, or -1 (EADDRINUSE: another tracker holds the URL). */
static int claim_url(const char *lcm_url)
{
    struct sockaddr_un address;
    char key[4096];
    int length, fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) {
        return -1;
    }
    url_key(lcm_url, key, sizeof key);
    memset(&address, 0, sizeof address);
    address.sun_family = AF_UNIX;
    length = snprintf(address.sun_path + 1, sizeof address.sun_path - 1, "hkf-track %s", key);
    if (length < 0 || length >= (int)sizeof address.sun_path - 1 || strlen(key) >= sizeof key - 1) {
        length = snprintf(address.sun_path + 1, sizeof address.sun_path - 1, "hkf-track #%016llx",
                          fnv1a(strlen(key) >= sizeof key - 1 ? lcm_url : key));
    }
    if (bind(fd, (const struct sockaddr *)&address, (socklen_t)(offsetof(struct sockaddr_un, sun_path) + 1 + length)) != 0) {
        const int reason = errno;
        close(fd);
        errno = reason;
        return -1;
    }
    return fd;
}

int track_exclusive_claim(track_exclusive_t *x, const char *lcm_url, const char *logs)
{
    x->url_socket = claim_url(lcm_url);
    if (x->url_socket < 0) {
        fprintf(stderr, "hkf-track: %s: %s\n", lcm_url,
                errno == EADDRINUSE ? "another hkf-track runs on this LCM URL (each would bridge both filters' poses); "
                                      "stop it, or give --lcm-url another port"
                                    : strerror(errno));
        return -1;
    }
    x->logs_folder = open(logs, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (x->logs_folder < 0 || flock(x->logs_folder, LOCK_EX | LOCK_NB) != 0) {
        fprintf(stderr, "hkf-track: %s: %s\n", logs,
                x->logs_folder >= 0 && errno == EWOULDBLOCK
                    ? "another hkf-track writes its logs in this folder; give --logs another one"
                    : strerror(errno));
        if (x->logs_folder >= 0) {
            close(x->logs_folder);
        }
        close(x->url_socket);
        x->url_socket = x->logs_folder = -1;
        return -1;
    }
    return 0;
}

void track_exclusive_release(track_exclusive_t *x)
{
    if (x->logs_folder >= 0) {
        close(x->logs_folder);
    }
    if (x->url_socket >= 0) {
        close(x->url_socket);
    }
    x->url_socket = x->logs_folder = -1;
}
