/*
 * hkf-bench-latency - raw -> filtered latency through a running hkf-filter.
 * Publishes raw head poses (HEAD_POSE_RAW) at a fixed rate, stamped with the
 * wall clock, receives the filtered poses (HEAD_POSE), and prints latency
 * percentiles (publish of the raw pose -> receipt of its filtered pose, i.e.
 * two LCM hops plus the filter) and how many raw poses got no answer.
 * Run it with dev/benchmarks/lcm_latency.sh, which starts hkf-filter in a
 * private network namespace.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lcm/lcm.h>

#include "bench_clock.h"
#include "head_motion_sim.h"
#include "hkf_head_pose_measurement_t.h"
#include "hkf_head_pose_t.h"

typedef struct {
    long count, sent;
    int64_t *published_us; /* per raw message: wall clock when published */
    double *latency_us;    /* per raw message: < 0 until answered */
    long answered, duplicates, unexpected;
} bench_t;

static void on_pose(const lcm_recv_buf_t *rbuf, const char *channel, const hkf_head_pose_t *pose, void *user)
{
    bench_t *b = user;
    const int64_t now = bench_wall_utime();
    /* raw message i is stamped published_us[i] (strictly increasing): find it */
    long low = 0, high = b->sent - 1, i = -1;
    (void)rbuf;
    while (low <= high) {
        const long mid = low + (high - low) / 2;
        if (b->published_us[mid] == pose->measurement_utime) {
            i = mid;
            break;
        }
        if (b->published_us[mid] < pose->measurement_utime) {
            low = mid + 1;
        } else {
            high = mid - 1;
        }
    }
    (void)channel;
    if (pose->extrapolated) {
        return;
    }
    if (i < 0 || i >= b->count) {
        ++b->unexpected;
        return;
    }
    if (b->latency_us[i] >= 0.0) {
        ++b->duplicates;
        return;
    }
    b->latency_us[i] = (double)(now - b->published_us[i]);
    ++b->answered;
}

static int compare_doubles(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    const char *url = "udpm://239.255.76.67:7667?ttl=0";
    double rate = 30.0, seconds = 10.0;
    bench_t b;
    lcm_t *lcm;
    sim_config_t config = sim_default_config();
    sim_t sim;
    double *sorted;
    long i, n = 0;
    int a;
    hkf_head_pose_t_subscription_t *sub;

    for (a = 1; a < argc; ++a) {
        if (strcmp(argv[a], "--version") == 0) {
            printf("hkf-bench-latency %s\n", HKF_VERSION);
            return 0;
        }
        if (strcmp(argv[a], "--help") == 0) {
            printf("usage: hkf-bench-latency [--rate HZ] [--seconds S] [--lcm-url URL]\n"
                   "Publishes HEAD_POSE_RAW at HZ (default 30) for S s (default 10) to a running\n"
                   "hkf-filter and prints raw->filtered latency percentiles and dropped messages.\n");
            return 0;
        } else if (strcmp(argv[a], "--rate") == 0 && a + 1 < argc) {
            rate = atof(argv[++a]);
        } else if (strcmp(argv[a], "--seconds") == 0 && a + 1 < argc) {
            seconds = atof(argv[++a]);
        } else if (strcmp(argv[a], "--lcm-url") == 0 && a + 1 < argc) {
            url = argv[++a];
        } else {
            fprintf(stderr, "hkf-bench-latency: unknown or incomplete argument '%s'\n", argv[a]);
            return 2;
        }
    }
    if (!(rate >= 1.0 && rate <= 20000.0) || !(seconds >= 0.1 && seconds <= 600.0)) {
        fprintf(stderr, "hkf-bench-latency: --rate 1..20000 Hz and --seconds 0.1..600 please\n");
        return 2;
    }
    lcm = lcm_create(url);
    if (lcm == NULL) {
        fprintf(stderr, "hkf-bench-latency: cannot open LCM provider '%s'\n", url);
        return 1;
    }
    memset(&b, 0, sizeof b);
    b.count = (long)(rate * seconds);
    b.latency_us = malloc((size_t)b.count * sizeof *b.latency_us);
    b.published_us = malloc((size_t)b.count * sizeof *b.published_us);
    sorted = malloc((size_t)b.count * sizeof *sorted);
    if (b.latency_us == NULL || b.published_us == NULL || sorted == NULL) {
        fprintf(stderr, "hkf-bench-latency: out of memory\n");
        return 1;
    }
    for (i = 0; i < b.count; ++i) {
        b.latency_us[i] = -1.0;
    }
    sub = hkf_head_pose_t_subscribe(lcm, "HEAD_POSE", on_pose, &b);
    hkf_head_pose_t_subscription_set_queue_capacity(sub, 100000); /* the measuring side must not drop */
    config.fps = rate;
    config.dropout_rate = 0.0; /* every raw pose should come back filtered */
    sim_init(&sim, &config, 1u);

    {
        const int64_t period = (int64_t)llround(1e6 / rate);
        const int64_t start = bench_wall_utime() + 200000;
        for (i = 0; i < b.count; ++i) {
            sim_frame_t frame;
            hkf_head_pose_measurement_t m;
            int64_t now;
            bench_handle_until(lcm, start + i * period);
            sim_next(&sim, &frame);
            memset(&m, 0, sizeof m);
            m.model = "fsanet";
            m.valid = 1;
            m.seq = i;
            m.pitch = (float)frame.measured[0];
            m.yaw = (float)frame.measured[1];
            m.roll = (float)frame.measured[2];
            now = bench_wall_utime();
            if (i > 0 && now <= b.published_us[i - 1]) {
                now = b.published_us[i - 1] + 1;
            }
            m.utime = now; /* the capture time: this frame is "captured" now */
            b.published_us[i] = now;
            b.sent = i + 1;
            hkf_head_pose_measurement_t_publish(lcm, "HEAD_POSE_RAW", &m);
        }
        bench_handle_until(lcm, bench_wall_utime() + 500000); /* late answers */
    }

    for (i = 0; i < b.count; ++i) {
        if (b.latency_us[i] >= 0.0) {
            sorted[n++] = b.latency_us[i];
        }
    }
    qsort(sorted, (size_t)n, sizeof *sorted, compare_doubles);
    if (n == 0) {
        printf("rate %.0f Hz: %ld sent, 0 answered\n", rate, b.count);
    } else {
        printf("rate %.0f Hz: %ld sent, %ld answered, %ld dropped; latency us: p50 %.0f, p99 %.0f, max %.0f\n", rate,
               b.count, b.answered, b.count - b.answered, sorted[n / 2], sorted[(long)(0.99 * (double)(n - 1))],
               sorted[n - 1]);
    }
    hkf_head_pose_t_unsubscribe(lcm, sub);
    lcm_destroy(lcm);
    free(b.latency_us);
    free(b.published_us);
    free(sorted);
    return n > 0 ? 0 : 1;
}
