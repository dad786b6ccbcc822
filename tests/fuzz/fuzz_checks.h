/*
 * fuzz_checks.h - the checks the hkf-filter fuzz targets share: a failed check
 * names the target and aborts, which libFuzzer reports as a finding.
 */
#ifndef FUZZ_CHECKS_H
#define FUZZ_CHECKS_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "hkf_head_pose_t.h"

static inline void fuzz_check(int condition, const char *target, const char *what)
{
    if (!condition) {
        fprintf(stderr, "%s: %s\n", target, what);
        abort();
    }
}

/* Every value of a pose hkf-filter would publish is finite, its variances positive, its status known. */
static inline void fuzz_check_pose(const hkf_head_pose_t *p, const char *target)
{
    int a;
    fuzz_check(isfinite(p->pitch) && isfinite(p->yaw) && isfinite(p->roll), target, "non-finite angle published");
    fuzz_check(isfinite(p->pitch_rate) && isfinite(p->yaw_rate) && isfinite(p->roll_rate), target,
               "non-finite rate published");
    for (a = 0; a < 3; ++a) {
        fuzz_check(isfinite(p->variance[a]) && p->variance[a] > 0, target, "variance not finite and positive");
        fuzz_check(isfinite(p->r[a]) && isfinite(p->center[a]), target, "non-finite R or centre published");
    }
    fuzz_check(p->status >= HKF_HEAD_POSE_T_TRACKING && p->status <= HKF_HEAD_POSE_T_LOST, target, "unknown status");
}

#endif /* FUZZ_CHECKS_H */
