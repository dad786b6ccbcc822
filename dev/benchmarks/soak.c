/*
 * hkf-soak - a long run through a live hkf-filter: publishes the simulated
 * drive's raw poses (with its dropouts and outliers, no estimator) at a fixed
 * rate, receives every filtered pose, and every interval prints one line: how
 * many were sent and answered, the latency percentiles of the interval, the
 * node's memory (VmRSS of --watch-pid), and any non-finite or out-of-order
 * pose. Ends with a summary; exit 1 if a measured pose got no answer, an
 * answer came out of order, or a pose was non-finite.
 * Run it with dev/benchmarks/soak.sh, which starts hkf-filter in a private
 * network namespace.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lcm/lcm.h>

#include "arguments.h"
#include "bench_clock.h"
#include "head_motion_sim.h"
#include "hkf_head_pose_measurement_t.h"
#include "hkf_head_pose_t.h"

#define LATENCY_BINS 100000 /* 1 us bins up to 100 ms; slower answers land in the last */

typedef struct {
    unsigned long counts[LATENCY_BINS];
    unsigned long total;
    double max_us;
} histogram_t;

#define QUEUE_SIZE (1L << 20) /* raw poses sent and not yet answered (17 min at 1 kHz) */

typedef struct {
    histogram_t interval, whole;
    int64_t sent_utime[QUEUE_SIZE]; /* a ring of the raw poses in flight, oldest first: */
    unsigned char sent_valid[QUEUE_SIZE];
    long head, tail;
    unsigned long sent_valid_count, answered, dropped, non_finite, unexpected;
} soak_t;

static void histogram_add(histogram_t *h, double us)
{
    const long bin = us < 0.0 ? 0 : us >= LATENCY_BINS - 1 ? LATENCY_BINS - 1 : (long)us;
    ++h->counts[bin];
    ++h->total;
    h->max_us = us > h->max_us ? us : h->max_us;
}

static double histogram_percentile(const histogram_t *h, double p)
{
    const unsigned long rank = (unsigned long)(p * (double)(h->total > 0 ? h->total - 1 : 0));
    unsigned long seen = 0;
    long bin;
    for (bin = 0; bin < LATENCY_BINS; ++bin) {
        seen += h->counts[bin];
        if (seen > rank) {
            return (double)bin;
        }
    }
    return 0.0;
}

static int pose_is_finite(const hkf_head_pose_t *p)
{
    int a, finite = isfinite(p->pitch) && isfinite(p->yaw) && isfinite(p->roll) && isfinite(p->pitch_rate) &&
                    isfinite(p->yaw_rate) && isfinite(p->roll_rate);
    for (a = 0; a < 3; ++a) {
        finite = finite && isfinite(p->variance[a]) && isfinite(p->r[a]) && isfinite(p->center[a]);
    }
    return finite;
}

static void on_pose(const lcm_recv_buf_t *rbuf, const char *channel, const hkf_head_pose_t *pose, void *user)
{
    soak_t *s = user;
    const double latency = (double)(bench_wall_utime() - pose->utime);
    (void)rbuf;
    (void)channel;
    if (!pose_is_finite(pose)) {
        ++s->non_finite;
    }
    if (pose->extrapolated) {
        return;
    }
    /* answers come in order: the raw poses before this one got none. A face-less
     * one gets none by design before the track starts; a measured one is dropped. */
    while (s->head != s->tail && s->sent_utime[s->head % QUEUE_SIZE] < pose->utime) {
        s->dropped += s->sent_valid[s->head % QUEUE_SIZE];
        ++s->head;
    }
    if (s->head == s->tail || s->sent_utime[s->head % QUEUE_SIZE] != pose->utime) {
        ++s->unexpected; /* an answer to nothing in flight: late, duplicate or out of order */
        return;
    }
    ++s->head;
    ++s->answered;
    histogram_add(&s->interval, latency);
    histogram_add(&s->whole, latency);
}

/* VmRSS of a process in KiB, or -1. */
static long rss_kib(long pid)
{
    char path[64], line[256];
    long kib = -1;
    FILE *f;
    snprintf(path, sizeof path, "/proc/%ld/status", pid);
    f = fopen(path, "r");
    if (f == NULL) {
        return -1;
    }
    while (fgets(line, sizeof line, f) != NULL) {
        if (sscanf(line, "VmRSS: %ld kB", &kib) == 1) {
            break;
        }
    }
    fclose(f);
    return kib;
}

int main(int argc, char **argv)
{
    static soak_t soak;
    const char *url = "udpm://239.255.76.67:7667?ttl=0";
    const char *csv_path = NULL;
    double rate = 1000.0, seconds = 60.0, interval_s = 10.0, pid = 0.0;
    sim_config_t config = sim_default_config();
    hkf_head_pose_t_subscription_t *sub;
    FILE *csv = NULL;
    lcm_t *lcm;
    sim_t sim;
    unsigned long sent = 0;
    long first_rss = -1, last_rss = -1, peak_rss = -1;
    int a;

    for (a = 1; a < argc; ++a) {
        const char *value = a + 1 < argc ? argv[a + 1] : NULL;
        int bad = 0;
        if (strcmp(argv[a], "--version") == 0) {
            printf("hkf-soak %s\n", HKF_VERSION);
            return 0;
        }
        if (strcmp(argv[a], "--help") == 0) {
            printf("usage: hkf-soak [--rate HZ] [--seconds S] [--interval S] [--watch-pid PID] [--csv FILE]\n"
                   "                [--lcm-url URL]\n"
                   "Publishes the simulated drive's raw poses at HZ (default 1000) for S s (default 60)\n"
                   "to a running hkf-filter; every interval (default 10 s) prints sent, answered, latency\n"
                   "p50/p99/max, non-finite poses and the VmRSS of PID (the node). --csv writes the lines\n"
                   "as CSV. Exit 1 if a measured pose got no answer or a pose was non-finite.\n");
            return 0;
        } else if (value == NULL) {
            bad = 1;
        } else if (strcmp(argv[a], "--rate") == 0) {
            bad = !argument_number(value, 1.0, 20000.0, &rate);
        } else if (strcmp(argv[a], "--seconds") == 0) {
            bad = !argument_number(value, 1.0, 7 * 86400.0, &seconds);
        } else if (strcmp(argv[a], "--interval") == 0) {
            bad = !argument_number(value, 0.1, 3600.0, &interval_s);
        } else if (strcmp(argv[a], "--watch-pid") == 0) {
            bad = !argument_number(value, 1.0, 4194304.0, &pid);
        } else if (strcmp(argv[a], "--csv") == 0) {
            csv_path = value;
        } else if (strcmp(argv[a], "--lcm-url") == 0) {
            url = value;
        } else {
            bad = 1;
        }
        if (bad) {
            fprintf(stderr, "hkf-soak: bad or incomplete argument '%s' (see --help)\n", argv[a]);
            return 2;
        }
        ++a;
    }
    lcm = lcm_create(url);
    if (lcm == NULL) {
        fprintf(stderr, "hkf-soak: cannot open LCM provider '%s'\n", url);
        return 1;
    }
    if (csv_path != NULL) {
        csv = fopen(csv_path, "w");
        if (csv == NULL) {
            fprintf(stderr, "hkf-soak: cannot write '%s'\n", csv_path);
            return 1;
        }
        fprintf(csv, "elapsed_s,sent,answered,dropped,p50_us,p99_us,max_us,rss_kib,non_finite\n");
    }
    sub = hkf_head_pose_t_subscribe(lcm, "HEAD_POSE", on_pose, &soak);
    hkf_head_pose_t_subscription_set_queue_capacity(sub, 100000); /* the measuring side must not drop */
    config.fps = rate;
    config.dropout_rate *= 30.0 / rate; /* the drive's face-less bursts as often per second as at 30 fps */
    sim_init(&sim, &config, 11u);
    printf("hkf-soak: %.0f Hz for %.0f s through hkf-filter; a line every %.0f s\n", rate, seconds, interval_s);
    printf("%9s %10s %10s %8s %8s %8s %8s %11s %10s\n", "elapsed s", "sent", "answered", "dropped", "p50 us",
           "p99 us", "max us", "node RSS", "non-finite");
    fflush(stdout);
    {
        const int64_t period = (int64_t)llround(1e6 / rate);
        const int64_t start = bench_wall_utime() + 200000, end = start + (int64_t)(seconds * 1e6);
        const int64_t step = (int64_t)(interval_s * 1e6);
        int64_t next_report = start + step, last_stamp = 0;
        unsigned long i;
        for (i = 0;; ++i) {
            const int64_t due = start + (int64_t)i * period;
            if (due >= next_report || due >= end) {
                bench_handle_until(lcm, bench_wall_utime() + 20000); /* the answers still in flight */
                last_rss = pid > 0 ? rss_kib((long)pid) : -1;
                first_rss = first_rss < 0 ? last_rss : first_rss;
                peak_rss = last_rss > peak_rss ? last_rss : peak_rss;
                printf("%9.0f %10lu %10lu %8lu %8.0f %8.0f %8.0f %7ld KiB %10lu\n", (double)(due - start) * 1e-6,
                       sent, soak.answered, soak.dropped, histogram_percentile(&soak.interval, 0.5),
                       histogram_percentile(&soak.interval, 0.99), soak.interval.max_us, last_rss, soak.non_finite);
                fflush(stdout);
                if (csv != NULL) {
                    fprintf(csv, "%.3f,%lu,%lu,%lu,%.0f,%.0f,%.0f,%ld,%lu\n", (double)(due - start) * 1e-6, sent,
                            soak.answered, soak.dropped, histogram_percentile(&soak.interval, 0.5),
                            histogram_percentile(&soak.interval, 0.99), soak.interval.max_us, last_rss,
                            soak.non_finite);
                    fflush(csv);
                }
                memset(&soak.interval, 0, sizeof soak.interval);
                next_report += step;
                if (due >= end) {
                    break;
                }
            }
            bench_handle_until(lcm, due);
            {
                sim_frame_t frame;
                hkf_head_pose_measurement_t m;
                int64_t now = bench_wall_utime();
                sim_next(&sim, &frame);
                memset(&m, 0, sizeof m);
                m.model = "fsanet";
                m.valid = frame.valid;
                m.seq = (int64_t)i + 1;
                m.pitch = (float)frame.measured[0];
                m.yaw = (float)frame.measured[1];
                m.roll = (float)frame.measured[2];
                now = now > last_stamp ? now : last_stamp + 1;
                m.utime = last_stamp = now; /* captured now: the answer's latency is receipt - utime */
                if (soak.tail - soak.head >= QUEUE_SIZE) { /* never answered for 17 min: dropped */
                    soak.dropped += soak.sent_valid[soak.head % QUEUE_SIZE];
                    ++soak.head;
                }
                soak.sent_utime[soak.tail % QUEUE_SIZE] = m.utime;
                soak.sent_valid[soak.tail % QUEUE_SIZE] = (unsigned char)(m.valid != 0);
                ++soak.tail;
                soak.sent_valid_count += m.valid != 0;
                hkf_head_pose_measurement_t_publish(lcm, "HEAD_POSE_RAW", &m);
                ++sent;
            }
        }
    }
    while (soak.head != soak.tail) { /* still unanswered at the end */
        soak.dropped += soak.sent_valid[soak.head % QUEUE_SIZE];
        ++soak.head;
    }
    printf("hkf-soak: %.0f s at %.0f Hz: %lu raw poses sent (%lu with a face), %lu answered, %lu with a face "
           "dropped, %lu unexpected; latency us p50 %.0f, p99 %.0f, p99.9 %.0f, max %.0f; %lu non-finite; "
           "node RSS %ld KiB first, %ld KiB last, %ld KiB peak (growth %+ld KiB)\n",
           seconds, rate, sent, soak.sent_valid_count, soak.answered, soak.dropped, soak.unexpected,
           histogram_percentile(&soak.whole, 0.5), histogram_percentile(&soak.whole, 0.99),
           histogram_percentile(&soak.whole, 0.999), soak.whole.max_us, soak.non_finite, first_rss, last_rss,
           peak_rss, first_rss >= 0 ? last_rss - first_rss : 0);
    hkf_head_pose_t_unsubscribe(lcm, sub);
    lcm_destroy(lcm);
    if (csv != NULL) {
        fclose(csv);
    }
    return soak.dropped == 0 && soak.unexpected == 0 && soak.non_finite == 0 && soak.answered > 0 ? 0 : 1;
}
