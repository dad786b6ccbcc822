/* model_name.c - see model_name.h. */
#include "model_name.h"

#include <ctype.h>
#include <stddef.h>

#include "hkf_head_pose_measurement_t.h"

int model_name_valid(const char *name)
{
    size_t i;
    for (i = 0; name[i] != '\0'; ++i) {
        if (i >= HKF_HEAD_POSE_MEASUREMENT_T_MODEL_NAME_MAX ||
            !(isalnum((unsigned char)name[i]) || name[i] == '_' || name[i] == '-')) {
            return 0;
        }
    }
    return i > 0;
}
