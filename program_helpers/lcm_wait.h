/*
 * lcm_wait.h - one wait of a live LCM loop that also keeps a timer (hkf-filter's
 * and hkf-opentrack's --rate): handle the next message if one arrives within
 * the wait, otherwise return so the caller can serve its timer or a stop request.
 */
#ifndef LCM_WAIT_H
#define LCM_WAIT_H

#include <stdint.h>

#include <lcm/lcm.h>

#ifdef __cplusplus
extern "C" {
#endif

/* How many received messages a subscription may hold before LCM drops new
 * ones: 1 s at 1 kHz. LCM's default, 30, is 30 ms at 1 kHz, and a node that
 * the scheduler starves that long (a busy machine) silently lost messages in
 * the soak. Each message takes microseconds, so a backlog clears at once. */
#define LCM_WAIT_QUEUE_CAPACITY 1000

/* lcm_subscribe with LCM_WAIT_QUEUE_CAPACITY; NULL (reported on stderr,
 * prefixed by `program`) when LCM refuses. */
lcm_subscription_t *lcm_wait_subscribe(lcm_t *lcm, const char *channel, lcm_msg_handler_t handler, void *user,
                                       const char *program);

/* SIGINT, SIGTERM and SIGHUP (the terminal closed) only set a flag, which the loop polls to stop with a summary. */
void lcm_wait_stop_on_signals(void);
int lcm_wait_stop_requested(void);
/* The signal that requested the stop (SIGINT, SIGTERM or SIGHUP), or 0. */
int lcm_wait_stop_signal(void);

/* The longest wait, so that a stop request (a signal) is noticed promptly. */
#define LCM_WAIT_MAX_US 100000

/* How long to wait: until next_tick_us (on the same clock as now_us), at most
 * LCM_WAIT_MAX_US, never negative; with no timer (next_tick_us = 0) the maximum. */
int64_t lcm_wait_time(int64_t next_tick_us, int64_t now_us);

/* Waits up to wait_us for a message and handles it. Returns 1 when one was
 * handled, 0 when none came (time out, or a signal), -1 on a failure, which
 * it reports on stderr prefixed by `program`. */
int lcm_wait_and_handle(lcm_t *lcm, int64_t wait_us, const char *program);

#ifdef __cplusplus
}
#endif

#endif /* LCM_WAIT_H */
