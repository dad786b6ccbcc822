/*
 * node_pose.h - a published pose, filled (filter_node.h states the rules): the angles' output at a capture time,
 * never stamped earlier than the pose published before it (moved on to that pose's time), the centre, the
 * position at that time (node_position.h), the node's sequence and counts.
 */
#ifndef NODE_POSE_H
#define NODE_POSE_H

#include <stdint.h>

#include "filter_node.h"

#ifdef __cplusplus
extern "C" {
#endif

/* *pose from out at capture time utime (moved on to the last pose's time when earlier: hkf_extrapolate); it is
 * the node's newest published pose from then on. */
void node_pose_fill(filter_node_t *node, const hkf_output_t *out, int64_t utime, hkf_head_pose_t *pose);

#ifdef __cplusplus
}
#endif

#endif /* NODE_POSE_H */
