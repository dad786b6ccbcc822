/*
 * bench_clock.h - what the live LCM benchmarks (hkf-bench-latency, hkf-soak)
 * share: the wall clock their stamps use, and handling messages until a time.
 */
#ifndef BENCH_CLOCK_H
#define BENCH_CLOCK_H

#include <stdint.h>

#include <lcm/lcm.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The wall clock in us since the Unix epoch: what capture stamps and hkf-filter use. */
int64_t bench_wall_utime(void);

/* Handles every message that arrives until the wall clock reaches `until`. */
void bench_handle_until(lcm_t *lcm, int64_t until);

#ifdef __cplusplus
}
#endif

#endif /* BENCH_CLOCK_H */
