/*
 * bench_clock.c - see bench_clock.h.
 */
#define _POSIX_C_SOURCE 200809L

#include "bench_clock.h"
#include "clocks.h"

#include <sys/select.h>
#include <time.h>

int64_t bench_wall_utime(void)
{
    return clock_wall_us();
}

void bench_handle_until(lcm_t *lcm, int64_t until)
{
    for (;;) {
        const int64_t left = until - bench_wall_utime();
        fd_set readable;
        struct timeval timeout;
        const int fd = lcm_get_fileno(lcm);
        if (left <= 0) {
            return;
        }
        FD_ZERO(&readable);
        FD_SET(fd, &readable);
        timeout.tv_sec = (time_t)(left / 1000000);
        timeout.tv_usec = (suseconds_t)(left % 1000000);
        if (select(fd + 1, &readable, NULL, NULL, &timeout) > 0) {
            lcm_handle(lcm);
        }
    }
}
