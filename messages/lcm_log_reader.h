/*
 * lcm_log_reader.h - reads an LCM log file (the format lcm-logger writes) with
 * every length checked against the file, for logs that may be hostile or
 * damaged. liblcm's reader gives up at the first bad event and believes any
 * data length up to 2 GB; this one skips over damage to the next event and
 * reports what it skipped and where the file was cut off.
 *
 * An event on disk (big-endian): sync word 0xEDA1DA01, event number (int64),
 * timestamp in us (int64), channel length (int32), data length (int32), the
 * channel's bytes, the data's bytes.
 */
#ifndef LCM_LOG_READER_H
#define LCM_LOG_READER_H

#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

#define LCM_LOG_SYNC_WORD 0xEDA1DA01u
#define LCM_LOG_CHANNEL_MAX 255 /* bytes; lcm-logger writes at most 63 */

typedef struct {
    int64_t eventnum, timestamp;
    char channel[LCM_LOG_CHANNEL_MAX + 1]; /* NUL-terminated */
    int32_t datalen;                       /* the event's data length */
    int data_read;                         /* 1: the data is in the caller's buffer; 0: too large, skipped */
} lcm_log_event_t;

typedef struct {
    FILE *f;
    long size;              /* bytes in the file */
    long position;          /* where the next event is looked for */
    long whole_end;         /* end of the last whole event */
    long skipped;           /* bytes between whole events that were no event (damage) */
    unsigned long events;   /* whole events read */
} lcm_log_reader_t;

/* Starts reading f (a seekable file) from its beginning; -1 if it is not seekable. */
int lcm_log_reader_open(lcm_log_reader_t *reader, FILE *f);

/* Reads the next whole event; its data goes into `data` when it has at most
 * `capacity` bytes, otherwise it is skipped (event->data_read = 0). Returns 1
 * for an event, 0 at the end of the file. Bytes that are not part of a whole
 * event are skipped: those between events add to reader->skipped, those after
 * the last one are the cut (lcm_log_reader_cut). */
int lcm_log_reader_next(lcm_log_reader_t *reader, lcm_log_event_t *event, void *data, int capacity);

/* After the end: how many bytes at the end of the file belong to no whole
 * event (a log cut off mid-event by a power loss or a full disk). */
long lcm_log_reader_cut(const lcm_log_reader_t *reader);

#ifdef __cplusplus
}
#endif

#endif /* LCM_LOG_READER_H */
