/* node_await.c - see node_await.h. */
#include "node_await.h"

#include "node_pose.h"

void node_await_queue(filter_node_t *node, const hkf_head_pose_t *pose)
{
    if (node->queued_count < FILTER_NODE_QUEUED) {
        node->queued[(node->queued_first + node->queued_count++) % FILTER_NODE_QUEUED] = *pose;
    }
}

int node_await_unqueue(filter_node_t *node, hkf_head_pose_t *pose)
{
    if (node->queued_count == 0) {
        return 0;
    }
    *pose = node->queued[node->queued_first];
    node->queued_first = (node->queued_first + 1) % FILTER_NODE_QUEUED;
    --node->queued_count;
    return 1;
}

/* The oldest waiting frame settled without its answer (second_model_settle), its own step's pose into *pose
 * unless a later pose is out already. Returns -1 when no frame waits, else whether *pose is to be published. */
static int settle_oldest(filter_node_t *node, hkf_head_pose_t *pose)
{
    const second_model_frame_t *frame;
    second_model_track_t track;
    track.filter = &node->filter;
    track.calibration = &node->calibration;
    if (!second_model_settle(&node->second, &node->models, &track, &frame)) {
        return -1;
    }
    node_rest_keep(&node->rest, &node->filter); /* the frames redone from before the player's rest or RECENTER */
    ++node->counts.awaits_expired;
    if (frame->utime <= node->published_utime) {
        return 0;
    }
    node_pose_fill(node, &track.posterior, frame->utime, pose);
    pose->measurement_utime = frame->utime;
    return 1;
}

void node_await_settle(filter_node_t *node, int64_t due_by, int64_t older_than)
{
    const second_model_frame_t *frame;
    hkf_head_pose_t pose;
    while ((frame = second_model_waiting(&node->second)) != NULL &&
           (second_model_deadline(&node->second) <= due_by || frame->utime < older_than)) {
        if (settle_oldest(node, &pose) > 0) {
            node_await_queue(node, &pose);
        }
    }
}

void node_await_settle_all(filter_node_t *node)
{
    node_await_settle(node, INT64_MAX, INT64_MIN);
}

int64_t filter_node_await_due(const filter_node_t *node)
{
    return node->queued_count > 0 ? 1 : second_model_deadline(&node->second);
}

int filter_node_await_next(filter_node_t *node, int64_t now, hkf_head_pose_t *pose, int64_t *due)
{
    int result;
    if (node_await_unqueue(node, pose)) {
        *due = now;
        return 1;
    }
    while ((*due = second_model_deadline(&node->second)) != 0 && *due <= now) {
        if ((result = settle_oldest(node, pose)) != 0) {
            return result > 0;
        }
    }
    return 0;
}
