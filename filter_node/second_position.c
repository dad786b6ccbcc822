/* second_position.c - see second_position.h. */
#include "second_position.h"

#include <string.h>

void second_position_init(second_position_t *p)
{
    memset(p, 0, sizeof *p);
    second_position_forget_frames(p);
}

void second_position_forget_frames(second_position_t *p)
{
    for (int i = 0; i < FILTER_NODE_POSITION_FRAMES; ++i) {
        p->frames[i].seq = -1;
    }
}

static int slot(int64_t seq)
{
    const int64_t r = seq % FILTER_NODE_POSITION_FRAMES;
    return (int)(r < 0 ? r + FILTER_NODE_POSITION_FRAMES : r);
}

void second_position_note_first(second_position_t *p, int64_t seq, int64_t utime, int measured, const float xyz[3])
{
    const int i = slot(seq);
    p->frames[i].seq = seq;
    p->frames[i].utime = utime;
    p->frames[i].measured = measured;
    memcpy(p->frames[i].xyz, xyz, sizeof p->frames[i].xyz);
}

int second_position_take(second_position_t *p, int64_t seq, int64_t utime, const float xyz[3], float out[3])
{
    const int i = slot(seq);
    int a;
    if (p->frames[i].seq != seq || p->frames[i].utime != utime) {
        return 0; /* not a kept frame of the first model */
    }
    if (p->frames[i].measured) { /* both measured: the running mean of first minus second */
        const long n = p->offset_frames < FILTER_NODE_POSITION_ALIGN ? p->offset_frames + 1 : FILTER_NODE_POSITION_ALIGN;
        for (a = 0; a < 3; ++a) {
            p->offset[a] += (p->frames[i].xyz[a] - xyz[a] - p->offset[a]) / (float)n;
        }
        p->offset_frames = n;
        return 0;
    }
    if (p->offset_frames < FILTER_NODE_POSITION_MIN_ALIGN) {
        return 0;
    }
    for (a = 0; a < 3; ++a) {
        out[a] = xyz[a] + p->offset[a];
    }
    return 1;
}
