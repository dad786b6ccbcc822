/*
 * lcm_log_reader.c - a bounded LCM log reader (see lcm_log_reader.h).
 */
#include "lcm_log_reader.h"

#include <string.h>

#define HEADER_BYTES 28 /* sync word, event number, timestamp, two lengths */

static uint64_t big_endian(const unsigned char *bytes, int count)
{
    uint64_t value = 0;
    int i;
    for (i = 0; i < count; ++i) {
        value = (value << 8) | bytes[i];
    }
    return value;
}

int lcm_log_reader_open(lcm_log_reader_t *reader, FILE *f)
{
    memset(reader, 0, sizeof *reader);
    reader->f = f;
    if (fseek(f, 0, SEEK_END) != 0 || (reader->size = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        return -1;
    }
    return 0;
}

/* The offset of the next sync word at or after `from`, or -1 if none. */
static long find_sync(lcm_log_reader_t *reader, long from)
{
    uint32_t window = 0;
    long position = from;
    int c;
    if (fseek(reader->f, from, SEEK_SET) != 0) {
        return -1;
    }
    while ((c = fgetc(reader->f)) != EOF) {
        window = (window << 8) | (uint32_t)c;
        ++position;
        if (window == LCM_LOG_SYNC_WORD && position - from >= 4) {
            return position - 4;
        }
    }
    return -1;
}

/* Reads the event whose sync word is at `start`; 1 if it is whole and sane. */
static int read_event_at(lcm_log_reader_t *reader, long start, lcm_log_event_t *event, void *data, int capacity)
{
    unsigned char header[HEADER_BYTES];
    int64_t channel_length, data_length;
    if (start > reader->size - HEADER_BYTES || fseek(reader->f, start, SEEK_SET) != 0 ||
        fread(header, 1, sizeof header, reader->f) != sizeof header) {
        return 0;
    }
    event->eventnum = (int64_t)big_endian(header + 4, 8);
    event->timestamp = (int64_t)big_endian(header + 12, 8);
    channel_length = (int32_t)(uint32_t)big_endian(header + 20, 4);
    data_length = (int32_t)(uint32_t)big_endian(header + 24, 4);
    if (channel_length < 1 || channel_length > LCM_LOG_CHANNEL_MAX || data_length < 0 ||
        channel_length + data_length > reader->size - start - HEADER_BYTES) {
        return 0; /* damaged, or cut off: it claims more bytes than the file has */
    }
    if (fread(event->channel, 1, (size_t)channel_length, reader->f) != (size_t)channel_length) {
        return 0;
    }
    event->channel[channel_length] = '\0';
    if (strlen(event->channel) != (size_t)channel_length) {
        return 0; /* a NUL inside a channel name: damage */
    }
    event->datalen = (int32_t)data_length;
    event->data_read = data_length <= capacity;
    if (event->data_read && fread(data, 1, (size_t)data_length, reader->f) != (size_t)data_length) {
        return 0;
    }
    reader->position = start + HEADER_BYTES + (long)channel_length + (long)data_length;
    return 1;
}

int lcm_log_reader_next(lcm_log_reader_t *reader, lcm_log_event_t *event, void *data, int capacity)
{
    long from = reader->position;
    for (;;) {
        const long start = find_sync(reader, from);
        if (start < 0) {
            return 0;
        }
        if (read_event_at(reader, start, event, data, capacity)) {
            reader->skipped += start - reader->whole_end;
            reader->whole_end = reader->position;
            ++reader->events;
            return 1;
        }
        from = start + 1; /* not an event after all: look further */
    }
}

long lcm_log_reader_cut(const lcm_log_reader_t *reader)
{
    return reader->size - reader->whole_end;
}
