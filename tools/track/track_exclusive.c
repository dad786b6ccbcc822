/* track_exclusive.c - see track_exclusive.h. */
#define _GNU_SOURCE /* flock's LOCK_* names with c99 */

#include "track_exclusive.h"

#include <errno.h>
#include <fcntl.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <sys/file.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

/* Binds the abstract socket "\0hkf-track <url>" (the name cut to what sun_path holds). The socket,
 * or -1 (EADDRINUSE: another tracker holds the URL). */
static int claim_url(const char *lcm_url)
{
    struct sockaddr_un address;
    int length, fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) {
        return -1;
    }
    memset(&address, 0, sizeof address);
    address.sun_family = AF_UNIX;
    length = snprintf(address.sun_path + 1, sizeof address.sun_path - 1, "hkf-track %s", lcm_url);
    if (length < 0 || length >= (int)sizeof address.sun_path - 1) {
        length = (int)sizeof address.sun_path - 2;
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
