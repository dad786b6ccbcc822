/*
 * view_listen.h - where the live view listens ([HOST:]PORT, as hkf-view --listen and hkf-track --view take
 * it) and where its page's files are.
 */
#ifndef VIEW_LISTEN_H
#define VIEW_LISTEN_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define VIEW_DEFAULT_HOST "127.0.0.1"
#define VIEW_DEFAULT_PORT "7670"

/* text: PORT or HOST:PORT, HOST an IPv4 literal (or localhost: 127.0.0.1), PORT 1 to 65535. 0 with host
 * (at least 64 characters) and port set, or -1 with the reason in reason. */
int view_listen_parse(const char *text, char *host, size_t host_size, unsigned *port, char *reason,
                      size_t reason_size);

/* The page's folder: share/hkf/view beside the program's bin/ when it has index.html, else the source
 * tree's (a build tree). */
void view_default_assets(char *out, size_t size);

#ifdef __cplusplus
}
#endif

#endif /* VIEW_LISTEN_H */
