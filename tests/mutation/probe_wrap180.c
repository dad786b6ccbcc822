/*
 * probe_wrap180.c - the probe behind mutant EQUIVALENT "hkf_wrap180's last
 * correction (>= 180) made > 180" (tests/mutation/mutants.txt): in the float
 * and double builds the branch `else if (w >= 180)` of hkf_wrap180
 * (libhkf/src/hkf_math.h) is never taken, because 1/360 rounds *up* in both
 * types, so the number of turns is never one short; the mutant, which only
 * changes that branch, therefore changes nothing. The probe runs libhkf's own
 * hkf_wrap180 and the mutant's formula side by side on every whole and half
 * multiple of 180 in the accepted range (|x| <= 3 HKF_MAX_ABS_ANGLE, what
 * callers pass) and on 20 million random values, and counts where they
 * differ. Built and run by ./run mutate; exit 1 on any difference.
 */
#include <stdio.h>
#include <stdlib.h>

#include "hkf/hkf.h"
#include "hkf_internal.h"
#include "hkf_math.h"

static hkf_real_t mutant(hkf_real_t x)
{
    int turns;
    hkf_real_t w;
    if (x >= HKF_REAL(-180.0) && x < HKF_REAL(180.0)) {
        return x;
    }
    turns = (int)((x + HKF_REAL(180.0)) * HKF_REAL(0.0027777777777777778));
    w = x - HKF_REAL(360.0) * (hkf_real_t)turns;
    if (w < HKF_REAL(-180.0)) {
        w += HKF_REAL(360.0);
    } else if (w > HKF_REAL(180.0)) {
        w -= HKF_REAL(360.0);
    }
    return w;
}

int main(void)
{
    const double range = 3.0 * HKF_MAX_ABS_ANGLE;
    long tried = 0, differ = 0, i;
    unsigned long state = 12345u;
    for (i = -(long)(range / 90.0); i <= (long)(range / 90.0); ++i) { /* every multiple of 90 */
        const hkf_real_t x = (hkf_real_t)(90.0 * (double)i);
        differ += hkf_wrap180(x) != mutant(x);
        ++tried;
    }
    for (i = 0; i < 20000000; ++i) {
        hkf_real_t x;
        state = state * 6364136223846793005ul + 1442695040888963407ul;
        x = (hkf_real_t)(((double)(state >> 11) / 9007199254740992.0 * 2.0 - 1.0) * range);
        differ += hkf_wrap180(x) != mutant(x);
        ++tried;
    }
    printf("probe_wrap180 (%s): %ld values, %ld where hkf_wrap180 and the mutant differ\n",
           sizeof(hkf_real_t) == sizeof(float) ? "float" : "double", tried, differ);
    return differ == 0 ? 0 : 1;
}
