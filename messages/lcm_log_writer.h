/*
 * lcm_log_writer.h - writes an LCM log file (the format of lcm-logger, read by
 * lcm-logplayer and lcm_log_reader.h) with every write checked. liblcm's
 * lcm_eventlog_destroy closes the file without looking at the result, so a
 * log cut by a full disk would pass as whole.
 */
#ifndef LCM_LOG_WRITER_H
#define LCM_LOG_WRITER_H

#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    FILE *f;
    int64_t events;  /* written so far: the next event's number */
    int failed;      /* a write failed: the log is cut (a full disk, an I/O error) */
} lcm_log_writer_t;

/* Starts a log on f, opened for writing (see safe_files.h); the writer owns it. */
void lcm_log_writer_start(lcm_log_writer_t *writer, FILE *f);

/* Appends one event; -1 (and writer->failed) when the write failed. */
int lcm_log_writer_write(lcm_log_writer_t *writer, int64_t timestamp, const char *channel, const void *data,
                         int32_t size);

/* Closes the log: 0 when every event and the close reached the file, else -1. */
int lcm_log_writer_close(lcm_log_writer_t *writer);

#ifdef __cplusplus
}
#endif

#endif /* LCM_LOG_WRITER_H */
