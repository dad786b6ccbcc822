/*
 * node_await.h - the frames that wait for the second model's answer, published one pose per frame and in
 * order (filter_node.h states the rule): a waiting frame settled without its answer (second_model_settle) at its
 * deadline, before a later frame's pose, or before a command, a restart or a new clock forgets it; the poses
 * that one call makes due beyond the one it returns wait in the node's queue (filter_node_await_next).
 */
#ifndef NODE_AWAIT_H
#define NODE_AWAIT_H

#include <stdint.h>

#include "filter_node.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The waiting frames, oldest first, whose deadline is at or before due_by or that are older than older_than,
 * settled without their answer; their poses (each unless a later pose is out already) queued. */
void node_await_settle(filter_node_t *node, int64_t due_by, int64_t older_than);

/* Every waiting frame settled (node_await_settle). */
void node_await_settle_all(filter_node_t *node);

/* A pose into the queue, behind those there (FILTER_NODE_QUEUED: the kept frames and one more, never full). */
void node_await_queue(filter_node_t *node, const hkf_head_pose_t *pose);

/* The queue's first pose into *pose: 1, or 0 when it is empty. */
int node_await_unqueue(filter_node_t *node, hkf_head_pose_t *pose);

#ifdef __cplusplus
}
#endif

#endif /* NODE_AWAIT_H */
