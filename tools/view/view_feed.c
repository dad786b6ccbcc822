/* view_feed.c - see view_feed.h. */
#define _POSIX_C_SOURCE 200809L

#include "view_feed.h"

#include <errno.h>
#include <string.h>
#include <time.h>

int view_feed_init(view_feed_t *feed)
{
    pthread_condattr_t monotonic;
    memset(feed, 0, sizeof *feed);
    if (pthread_condattr_init(&monotonic) != 0) {
        return -1;
    }
    (void)pthread_condattr_setclock(&monotonic, CLOCK_MONOTONIC);
    if (pthread_mutex_init(&feed->lock, NULL) != 0) {
        (void)pthread_condattr_destroy(&monotonic);
        return -1;
    }
    if (pthread_cond_init(&feed->changed, &monotonic) != 0) {
        (void)pthread_condattr_destroy(&monotonic);
        (void)pthread_mutex_destroy(&feed->lock);
        return -1;
    }
    (void)pthread_condattr_destroy(&monotonic);
    return 0;
}

void view_feed_destroy(view_feed_t *feed)
{
    (void)pthread_cond_destroy(&feed->changed);
    (void)pthread_mutex_destroy(&feed->lock);
}

void view_feed_write(view_feed_t *feed, const char *json)
{
    pthread_mutex_lock(&feed->lock);
    {
        char *slot = feed->event[feed->written % VIEW_FEED_EVENTS];
        strncpy(slot, json, VIEW_FEED_EVENT_SIZE - 1);
        slot[VIEW_FEED_EVENT_SIZE - 1] = '\0';
        ++feed->written;
    }
    pthread_cond_broadcast(&feed->changed);
    pthread_mutex_unlock(&feed->lock);
}

int view_feed_keep_picture(view_feed_t *feed, const void *jpeg, size_t size)
{
    if (size == 0 || size > VIEW_FEED_PICTURE_SIZE) {
        return -1;
    }
    pthread_mutex_lock(&feed->lock);
    memcpy(feed->picture, jpeg, size);
    feed->picture_size = size;
    ++feed->pictures;
    pthread_mutex_unlock(&feed->lock);
    return 0;
}

/* Waits on the feed's condition until an event past cursor, the close, or wait_ms. Called locked. */
static void wait_for_event(view_feed_t *feed, uint64_t cursor, int wait_ms)
{
    struct timespec until;
    clock_gettime(CLOCK_MONOTONIC, &until);
    until.tv_sec += wait_ms / 1000;
    until.tv_nsec += (long)(wait_ms % 1000) * 1000000L;
    if (until.tv_nsec >= 1000000000L) {
        until.tv_sec += 1;
        until.tv_nsec -= 1000000000L;
    }
    while (feed->written <= cursor && !feed->closing) {
        if (pthread_cond_timedwait(&feed->changed, &feed->lock, &until) == ETIMEDOUT) {
            break;
        }
    }
}

long view_feed_read(view_feed_t *feed, uint64_t *cursor, char *out, size_t size, int wait_ms)
{
    size_t used = 0;
    long result;
    pthread_mutex_lock(&feed->lock);
    wait_for_event(feed, *cursor, wait_ms);
    if (feed->closing) {
        pthread_mutex_unlock(&feed->lock);
        return -1;
    }
    if (feed->written > VIEW_FEED_EVENTS && *cursor < feed->written - VIEW_FEED_EVENTS) {
        feed->skipped += (long)(feed->written - VIEW_FEED_EVENTS - *cursor); /* a ring behind: skip ahead */
        *cursor = feed->written - VIEW_FEED_EVENTS;
    }
    while (*cursor < feed->written) {
        const char *event = feed->event[*cursor % VIEW_FEED_EVENTS];
        const size_t length = strlen(event);
        if (used + length + 8 > size) {
            break;
        }
        memcpy(out + used, "data: ", 6);
        memcpy(out + used + 6, event, length);
        memcpy(out + used + 6 + length, "\n\n", 2);
        used += length + 8;
        ++*cursor;
    }
    result = (long)used;
    pthread_mutex_unlock(&feed->lock);
    return result;
}

size_t view_feed_picture(view_feed_t *feed, unsigned char *out, size_t size)
{
    size_t copied = 0;
    pthread_mutex_lock(&feed->lock);
    if (feed->picture_size > 0 && feed->picture_size <= size) {
        memcpy(out, feed->picture, feed->picture_size);
        copied = feed->picture_size;
    }
    pthread_mutex_unlock(&feed->lock);
    return copied;
}

void view_feed_close(view_feed_t *feed)
{
    pthread_mutex_lock(&feed->lock);
    feed->closing = 1;
    pthread_cond_broadcast(&feed->changed);
    pthread_mutex_unlock(&feed->lock);
}
