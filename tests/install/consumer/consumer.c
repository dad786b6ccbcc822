/* Filters three measurements with an installed libhkf; exits 0 when the
 * posterior lies between the first and the last measurement. */
#include <stdio.h>
#include "hkf/hkf.h"

int main(void)
{
    hkf_filter_t f;
    hkf_output_t out;
    const hkf_real_t z[3][3] = {{0, 10, 0}, {0, 11, 0}, {0, 12, 0}};
    int i;
    if (hkf_init(&f, &hkf_default_settings) != HKF_OK) {
        return 1;
    }
    for (i = 0; i < 3; ++i) {
        if (hkf_update(&f, z[i], (hkf_real_t)(1.0 / 30.0), &out) != HKF_OK) {
            return 1;
        }
    }
    printf("yaw %.3f, %d-byte filter\n", (double)out.angle[1], (int)sizeof f);
    return out.angle[1] > 10 && out.angle[1] < 12 ? 0 : 1;
}
