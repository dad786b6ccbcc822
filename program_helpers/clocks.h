/*
 * clocks.h - the clocks the programs stamp and wait with, in microseconds.
 */
#ifndef CLOCKS_H
#define CLOCKS_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The wall clock (capture stamps, as the estimator writes them). */
int64_t clock_wall_us(void);

/* The monotonic clock (waits and arrival times): it never steps. */
int64_t clock_monotonic_us(void);

#ifdef __cplusplus
}
#endif

#endif /* CLOCKS_H */
