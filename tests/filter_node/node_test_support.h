/*
 * node_test_support.h - what the filter node's tests share (tests/filter_node/test_node_*.c): a
 * node with the default config, measurements of one estimator, libhkf's reference step, and
 * streams fed through filter_node_receive. Include after cmocka.h.
 */
#ifndef NODE_TEST_SUPPORT_H
#define NODE_TEST_SUPPORT_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "filter_node.h"
#include "head_motion_sim.h"

#define T0 1700000000000000LL
#define FRAME_US 33333LL

static node_config_t config;
static filter_node_t node;

static inline int setup(void **state)
{
    (void)state;
    node_config_defaults(&config);
    config.rest.rest_time = 0; /* no rest asked for: the node is libhkf's filter (test_node_rest.c has the rest) */
    assert_int_equal(filter_node_init(&node, &config), 0);
    return 0;
}

/* The node with the rest as shipped (setup has none). */
static inline int setup_with_rest(void **state)
{
    (void)state;
    node_config_defaults(&config);
    assert_true(config.rest.rest_time > 0);
    assert_int_equal(filter_node_init(&node, &config), 0);
    return 0;
}

static int64_t next_seq; /* the estimator's frame counter: +1 per measurement made */

static inline hkf_head_pose_measurement_t measurement(int64_t utime, int valid, double pitch, double yaw, double roll)
{
    hkf_head_pose_measurement_t m;
    memset(&m, 0, sizeof m);
    m.seq = next_seq++;
    m.utime = utime;
    m.model = "fsanet";
    m.valid = valid;
    m.pitch = (float)pitch;
    m.yaw = (float)yaw;
    m.roll = (float)roll;
    return m;
}

/* The reference's step as the node makes it: an update (z) or a prediction (z NULL), then, when it was
 * made, the calibration beside the filter. The filter's result. */
static inline int reference_step(hkf_filter_t *f, hkf_calibration_t *c, const hkf_real_t *z, hkf_real_t dt, hkf_output_t *out)
{
    const int result = z != NULL ? hkf_update(f, z, dt, out) : hkf_predict(f, dt, out);
    if (result == HKF_OK) {
        assert_int_equal(hkf_calibration_update(c, f, z, dt), HKF_OK);
    }
    return result;
}

/* A published pose is the reference's posterior, at the measurement's time, in the reference's state. */
static inline void assert_pose_is(const hkf_head_pose_t *pose, const hkf_output_t *out, int64_t utime)
{
    assert_true(pose->yaw == out->angle[1] && pose->pitch == out->angle[0] && pose->roll == out->angle[2]);
    assert_true(pose->yaw_rate == out->rate[1] && pose->variance[1] == out->variance[1] && pose->r[2] == out->r[2]);
    assert_true(pose->utime == utime);
    assert_int_equal(pose->status, out->status == HKF_STATUS_TRACKING   ? HKF_HEAD_POSE_T_TRACKING
                                   : out->status == HKF_STATUS_COASTING ? HKF_HEAD_POSE_T_COASTING
                                                                        : HKF_HEAD_POSE_T_LOST);
}

/* Clock rule: feed n frames from frame `first`, capture stamps shifted by
 * stamp_shift_us, arriving on time; returns how many were published. */
static inline int feed(int first, int n, int64_t stamp_shift_us)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    int i, published = 0;
    for (i = first; i < first + n; ++i) {
        m = measurement(T0 + i * FRAME_US + stamp_shift_us, 1, 0, 10, 0);
        if (filter_node_receive(&node, &m, T0 + i * FRAME_US, &pose)) {
            assert_true(pose.utime == m.utime && isfinite(pose.yaw)); /* never a pose at a bad stamp */
            ++published;
        }
    }
    return published;
}

/* A mesh frame at utime with the position (x, y, z); both models' measurements of it go to the node
 * (the second's position `box_offset` cm farther in z), unless mesh_position is 0 (the mesh folds). */
static inline void feed_two_models(int64_t utime, int64_t arrival, float x, float z, int mesh_position, float box_offset,
                            hkf_head_pose_t *pose)
{
    hkf_head_pose_measurement_t first = measurement(utime, 1, 0, 5, 0), second;
    hkf_head_pose_t ignored;
    first.model = "mesh_pnp";
    if (mesh_position) {
        first.x = x, first.y = 0.0f, first.z = z;
    }
    second = first;
    second.model = "whenet";
    second.x = x, second.y = 0.0f, second.z = z + box_offset;
    (void)filter_node_receive(&node, &first, arrival, pose);
    (void)filter_node_receive(&node, &second, arrival + 1000, &ignored);
}

/* frames frames of the simulated drive as the first model's measurements (every tenth frame's face missed)
 * and a second model's of each (its own errors), and the reference's pair step on each, the calibration
 * beside it; the frames only the second model measured. */
static inline int make_pair_frames(hkf_head_pose_measurement_t *first, hkf_head_pose_measurement_t *second, int frames,
                            hkf_filter_t *reference, const hkf_model_noise_t *s2)
{
    sim_config_t sc = sim_default_config();
    sim_t sim;
    hkf_calibration_t calibration;
    int i, second_only = 0;
    assert_int_equal(hkf_calibration_init(&calibration, &config.calibration, reference), HKF_OK);
    sim_init(&sim, &sc, 5u);
    for (i = 0; i < frames; ++i) {
        sim_frame_t frame;
        const int64_t utime = T0 + i * FRAME_US;
        sim_next(&sim, &frame);
        first[i] = measurement(utime, frame.valid && i % 10 != 7, frame.measured[0], frame.measured[1], frame.measured[2]);
        second[i] = first[i];
        second[i].model = "hopenet";
        second[i].valid = 1;
        second[i].pitch = (float)(frame.truth[0] + 3.0 * sin(0.7 * i));
        second[i].yaw = (float)(frame.truth[1] - 2.0 * cos(1.3 * i));
        second[i].roll = (float)(frame.truth[2] + 2.5 * sin(2.1 * i));
        second_only += !first[i].valid;
        {
            const hkf_real_t z[3] = {first[i].pitch, first[i].yaw, first[i].roll};
            const hkf_real_t z2[3] = {second[i].pitch, second[i].yaw, second[i].roll};
            const hkf_real_t dt = (hkf_real_t)(i == 0 ? 0.0 : FRAME_US * 1e-6);
            assert_int_equal(hkf_update_pair(reference, first[i].valid ? z : NULL, z2, s2, dt, NULL), HKF_OK);
            assert_int_equal(hkf_calibration_update(&calibration, reference, first[i].valid ? z : z2, dt), HKF_OK);
        }
    }
    return second_only;
}

#endif /* NODE_TEST_SUPPORT_H */
