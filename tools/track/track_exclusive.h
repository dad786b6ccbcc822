/*
 * track_exclusive.h - one hkf-track per LCM URL and per log folder. Two
 * trackers on one URL would each bridge both filters' poses and mix them in
 * their status lines; two on one log folder would truncate each other's logs.
 *
 * The URL is claimed by binding an abstract Unix socket named after it: such
 * names live in the network namespace, as LCM's udpm multicast does, and the
 * kernel frees them when the process ends, however it ends. The folder is
 * claimed by flock(2) on the folder itself.
 */
#ifndef TRACK_EXCLUSIVE_H
#define TRACK_EXCLUSIVE_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    int url_socket; /* -1 when not held */
    int logs_folder;
} track_exclusive_t;

/* Claims lcm_url (resolved) and the folder logs (which exists). 0, or -1 with what holds them on stderr
 * (nothing is held then). */
int track_exclusive_claim(track_exclusive_t *x, const char *lcm_url, const char *logs);

/* Lets both go. */
void track_exclusive_release(track_exclusive_t *x);

#ifdef __cplusplus
}
#endif

#endif /* TRACK_EXCLUSIVE_H */
