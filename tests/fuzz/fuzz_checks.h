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

#ifdef __cplusplus
extern "C" {
#endif

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
    /* the position: none (all 0) or within the range hkf-filter takes (|x|, |y| <= 1000 cm, 1 <= z <= 1000) */
    for (a = 0; a < 3; ++a) {
        const float place[3] = {p->x, p->y, p->z}, rate[3] = {p->x_rate, p->y_rate, p->z_rate};
        fuzz_check(isfinite(place[a]) && isfinite(rate[a]) && isfinite(p->position_center[a]), target,
                   "non-finite position, rate or centre published");
        fuzz_check(fabsf(place[a]) <= 1000.f && fabsf(p->position_center[a]) <= 1000.f, target,
                   "a position beyond +-1000 cm published");
        fuzz_check(isfinite(p->position_variance[a]) && p->position_variance[a] >= 0, target,
                   "position variance not finite and >= 0");
    }
    fuzz_check(p->z == 0.f || p->z >= 1.f, target, "a position nearer than 1 cm published");
}

#ifdef __cplusplus
}
#endif

#endif /* FUZZ_CHECKS_H */
