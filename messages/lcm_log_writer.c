/* lcm_log_writer.c - see lcm_log_writer.h. */
#include "lcm_log_writer.h"

#include <string.h>

#include "lcm_log_reader.h"
#include "safe_files.h"

static void put_big_endian(unsigned char *bytes, uint64_t value, int count)
{
    int i;
    for (i = count - 1; i >= 0; --i) {
        bytes[i] = (unsigned char)(value & 0xff);
        value >>= 8;
    }
}

void lcm_log_writer_start(lcm_log_writer_t *writer, FILE *f)
{
    memset(writer, 0, sizeof *writer);
    writer->f = f;
}

int lcm_log_writer_write(lcm_log_writer_t *writer, int64_t timestamp, const char *channel, const void *data,
                         int32_t size)
{
    unsigned char header[28];
    const size_t channel_length = strlen(channel);
    if (writer->failed || channel_length < 1 || channel_length > LCM_LOG_CHANNEL_MAX || size < 0) {
        writer->failed = 1;
        return -1;
    }
    put_big_endian(header, LCM_LOG_SYNC_WORD, 4);
    put_big_endian(header + 4, (uint64_t)writer->events, 8);
    put_big_endian(header + 12, (uint64_t)timestamp, 8);
    put_big_endian(header + 20, (uint64_t)channel_length, 4);
    put_big_endian(header + 24, (uint64_t)(uint32_t)size, 4);
    if (fwrite(header, 1, sizeof header, writer->f) != sizeof header ||
        fwrite(channel, 1, channel_length, writer->f) != channel_length ||
        (size > 0 && fwrite(data, 1, (size_t)size, writer->f) != (size_t)size)) {
        writer->failed = 1;
        return -1;
    }
    ++writer->events;
    return 0;
}

int lcm_log_writer_close(lcm_log_writer_t *writer)
{
    const int closed = writer->f != NULL ? safe_close(writer->f) : 0;
    writer->f = NULL;
    return closed != 0 || writer->failed ? -1 : 0;
}
