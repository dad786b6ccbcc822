/*
 * second_position.h - a second model's positions, the node's side (filter_node.h
 * states the rule): where the first model measured no position (the mesh
 * folds at a profile; WHENet beside it still finds the face), the second
 * model's position - from its face box, coarser - stands in, moved onto the
 * first's frame by the running mean of their difference over the last frames
 * both measured (a face box's distance differs from the mesh's by a steady
 * few per cent: 2-4 cm at 60 cm, which would otherwise read as a lean each
 * time the mesh drops out).
 */
#ifndef SECOND_POSITION_H
#define SECOND_POSITION_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define FILTER_NODE_POSITION_FRAMES 32   /* the first model's last frames kept (as FILTER_NODE_PAIR_FRAMES) */
#define FILTER_NODE_POSITION_ALIGN 60    /* frames both measured that the offset averages */
#define FILTER_NODE_POSITION_MIN_ALIGN 5 /* frames both measured before the second's positions are used */

typedef struct {
    struct {
        int64_t seq, utime;
        int measured;     /* the first model measured a position: */
        float xyz[3];     /* cm */
    } frames[FILTER_NODE_POSITION_FRAMES]; /* by seq modulo FILTER_NODE_POSITION_FRAMES */
    float offset[3];      /* cm: first minus second, running mean */
    long offset_frames;   /* frames it has averaged (at most FILTER_NODE_POSITION_ALIGN) */
} second_position_t;

/* Empty: no frame kept, no offset. */
void second_position_init(second_position_t *p);

/* Forgets the kept frames (a restart, a new clock) and keeps the offset. */
void second_position_forget_frames(second_position_t *p);

/* Notes the first model's frame (seq, utime) and its position (measured: z > 0). */
void second_position_note_first(second_position_t *p, int64_t seq, int64_t utime, int measured, const float xyz[3]);

/* The second model's position xyz of frame (seq, utime): when the first model
 * measured one there, the offset learns from the pair and 0 is returned; when
 * it measured none and the offset has averaged enough frames, *out is xyz on
 * the first's frame and 1 is returned; otherwise (a frame no longer kept, or
 * not yet aligned) 0. */
int second_position_take(second_position_t *p, int64_t seq, int64_t utime, const float xyz[3], float out[3]);

#ifdef __cplusplus
}
#endif

#endif /* SECOND_POSITION_H */
