/* model_offset.c - see model_offset.h. */
#include "model_offset.h"

#include <string.h>

void model_offset_init(model_offset_t *o)
{
    memset(o, 0, sizeof *o);
}

void model_offset_learn(model_offset_t *o, const char *model, const double difference[3], long most)
{
    int a;
    if (strncmp(o->model, model, sizeof o->model) != 0) { /* another second model: start over */
        model_offset_init(o);
        strncpy(o->model, model, sizeof o->model - 1);
    }
    if (difference != NULL && most > 0) {
        const long n = o->frames < most ? o->frames + 1 : most;
        for (a = 0; a < 3; ++a) {
            o->offset[a] += (hkf_real_t)((difference[a] - (double)o->offset[a]) / (double)n);
        }
        o->frames = n;
    }
}
