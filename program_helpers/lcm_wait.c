/* lcm_wait.c - see lcm_wait.h. */
#define _POSIX_C_SOURCE 200809L

#include "lcm_wait.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/select.h>

static volatile sig_atomic_t stop_flag = 0;

static void on_stop_signal(int signal_number)
{
    stop_flag = signal_number;
}

void lcm_wait_stop_on_signals(void)
{
    struct sigaction action;
    memset(&action, 0, sizeof action);
    action.sa_handler = on_stop_signal;
    sigaction(SIGINT, &action, NULL);
    sigaction(SIGTERM, &action, NULL);
    sigaction(SIGHUP, &action, NULL); /* the terminal closed: stop with a summary too */
}

int lcm_wait_stop_requested(void)
{
    return stop_flag != 0;
}

int lcm_wait_stop_signal(void)
{
    return stop_flag;
}

int64_t lcm_wait_time(int64_t next_tick_us, int64_t now_us)
{
    const int64_t until = next_tick_us - now_us;
    if (next_tick_us == 0) {
        return LCM_WAIT_MAX_US;
    }
    return until < 0 ? 0 : (until < LCM_WAIT_MAX_US ? until : LCM_WAIT_MAX_US);
}

int lcm_wait_and_handle(lcm_t *lcm, int64_t wait_us, const char *program)
{
    const int fd = lcm_get_fileno(lcm);
    fd_set readable;
    struct timeval timeout;
    int ready;
    FD_ZERO(&readable);
    FD_SET(fd, &readable);
    timeout.tv_sec = (time_t)(wait_us / 1000000);
    timeout.tv_usec = (suseconds_t)(wait_us % 1000000);
    ready = select(fd + 1, &readable, NULL, NULL, &timeout);
    if (ready < 0) {
        if (errno == EINTR) {
            return 0;
        }
        fprintf(stderr, "%s: waiting for LCM messages failed: %s\n", program, strerror(errno));
        return -1;
    }
    if (ready > 0 && lcm_handle(lcm) != 0) {
        fprintf(stderr, "%s: LCM receive failed\n", program);
        return -1;
    }
    return ready > 0;
}

lcm_subscription_t *lcm_wait_subscribe(lcm_t *lcm, const char *channel, lcm_msg_handler_t handler, void *user,
                                       const char *program)
{
    lcm_subscription_t *subscription = lcm_subscribe(lcm, channel, handler, user);
    if (subscription == NULL) {
        fprintf(stderr, "%s: cannot subscribe to %s\n", program, channel);
        return NULL;
    }
    (void)lcm_subscription_set_queue_capacity(subscription, LCM_WAIT_QUEUE_CAPACITY);
    return subscription;
}
