/*
 * view_feed.h - what the live view's page is sent, between the LCM thread that writes it and the viewers'
 * threads that read it: a ring of the latest events (each one line of JSON) and the latest camera picture.
 * The writer never waits for a reader: a viewer that falls a ring behind skips to the oldest event kept,
 * so a slow or stalled viewer costs the tracker nothing.
 */
#ifndef VIEW_FEED_H
#define VIEW_FEED_H

#include <pthread.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define VIEW_FEED_EVENTS 2048        /* ~10 s of events at 60 fps with three per frame */
#define VIEW_FEED_EVENT_SIZE 480     /* bytes of one event's JSON, its end included */
#define VIEW_FEED_PICTURE_SIZE 262144 /* bytes of the largest camera picture (JPEG) kept */

typedef struct {
    pthread_mutex_t lock;
    pthread_cond_t changed;
    uint64_t written;                /* events ever written; event k is at k % VIEW_FEED_EVENTS */
    char event[VIEW_FEED_EVENTS][VIEW_FEED_EVENT_SIZE];
    unsigned char picture[VIEW_FEED_PICTURE_SIZE];
    size_t picture_size;             /* 0: none yet */
    uint64_t pictures;               /* pictures ever kept */
    int closing;                     /* the view stops: readers end their streams */
    long skipped;                    /* events readers skipped, having fallen a ring behind */
} view_feed_t;

/* 0, or -1 when the lock or condition could not be made. */
int view_feed_init(view_feed_t *feed);
void view_feed_destroy(view_feed_t *feed);

/* Appends one event (JSON text; cut at VIEW_FEED_EVENT_SIZE - 1, so the writer makes them shorter). */
void view_feed_write(view_feed_t *feed, const char *json);

/* Keeps a camera picture as the latest one; a larger one than VIEW_FEED_PICTURE_SIZE is dropped (-1). */
int view_feed_keep_picture(view_feed_t *feed, const void *jpeg, size_t size);

/* Copies as many whole events from *cursor on as fit in out as Server-Sent Events ("data: JSON\n\n") and
 * moves the cursor past them; waits up to wait_ms for one when there is none. Returns the bytes written:
 * 0 when none came in time; -1 once the feed is closing. */
long view_feed_read(view_feed_t *feed, uint64_t *cursor, char *out, size_t size, int wait_ms);

/* The latest picture copied into out (at most size bytes): its size, or 0 when there is none. */
size_t view_feed_picture(view_feed_t *feed, unsigned char *out, size_t size);

/* Readers end their streams. */
void view_feed_close(view_feed_t *feed);

#ifdef __cplusplus
}
#endif

#endif /* VIEW_FEED_H */
