/* view_listen.c - see view_listen.h. */
#define _POSIX_C_SOURCE 200809L

#include "view_listen.h"

#include <arpa/inet.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "arguments.h"

int view_listen_parse(const char *text, char *host, size_t host_size, unsigned *port, char *reason,
                      size_t reason_size)
{
    const char *colon = strrchr(text, ':');
    const char *port_text = colon != NULL ? colon + 1 : text;
    const size_t host_length = colon != NULL ? (size_t)(colon - text) : strlen(VIEW_DEFAULT_HOST);
    struct in_addr parsed;
    long number;
    if (argument_port(port_text, 1, &number) == 0) {
        snprintf(reason, reason_size, "'%s' has no port from 1 to 65535 ([HOST:]PORT)", text);
        return -1;
    }
    if (host_length == 0 || host_length >= host_size) {
        snprintf(reason, reason_size, "'%s' has no host before its port ([HOST:]PORT)", text);
        return -1;
    }
    memcpy(host, colon != NULL ? text : VIEW_DEFAULT_HOST, host_length);
    host[host_length] = '\0';
    if (strcmp(host, "localhost") == 0) {
        snprintf(host, host_size, "%s", VIEW_DEFAULT_HOST);
    }
    if (inet_pton(AF_INET, host, &parsed) != 1) {
        snprintf(reason, reason_size, "'%s' is not an IPv4 address (e.g. 127.0.0.1, or 0.0.0.0 for every one)", host);
        return -1;
    }
    *port = (unsigned)number;
    return 0;
}

void view_default_assets(char *out, size_t size)
{
    char self[4096], probe[4200];
    const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n > 0) {
        char *slash;
        self[n] = '\0';
        slash = strrchr(self, '/');
        if (slash != NULL) {
            *slash = '\0'; /* bin/ */
            snprintf(probe, sizeof probe, "%s/../share/hkf/view/index.html", self);
            if (access(probe, R_OK) == 0) {
                snprintf(out, size, "%s/../share/hkf/view", self);
                return;
            }
        }
    }
    snprintf(out, size, "%s", HKF_VIEW_SOURCE_ASSETS);
}
