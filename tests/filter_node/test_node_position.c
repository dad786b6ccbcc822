/*
 * test_node_position.c - hkf-filter's node (filter_node/filter_node.c), the position: filtered, gated, bounded and coasting, a second model's standing in, through clock steps and commands.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "node_test_support.h"

/* The position: filtered from the measurements that carry one (z > 0), published with its
 * centre; a message without one leaves it alone; RECENTER sets the centre, RESET forgets it;
 * a box-based model's position (its position_r_scale) moves the filter less than the mesh's (a deviation the size
 * of the measured noise: the filter is calibrated on the +-0.2 cm the positions carry). */
/* 30 mesh frames around (2, -1, 60) cm with +-0.2 cm of noise, then one without a position (held). */
static hkf_head_pose_t position_filtered_and_held(void)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    int i;
    m = measurement(T0, 1, 0, 0, 0);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    assert_true(pose.z == 0.0f && pose.position_center[2] == 0.0f); /* no position measured yet */
    for (i = 1; i <= 30; ++i) {
        const float noise = i % 2 ? 0.2f : -0.2f;
        m = measurement(T0 + i * FRAME_US, 1, 0, 0, 0);
        m.model = "mesh_pnp";
        m.x = 2.0f + 0.1f * noise, m.y = -1.0f, m.z = 60.0f + noise;
        assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    }
    assert_true(fabsf(pose.z - 60.0f) < 0.1f && fabsf(pose.x - 2.0f) < 0.05f);
    assert_true(fabsf(pose.position_center[2] - 60.2f) < 1e-4f); /* the first measurement */
    assert_true(pose.position_variance[2] > 0.0f && pose.position_variance[2] < 0.05f);
    {
        const float held = pose.z;
        m = measurement(T0 + 31 * FRAME_US, 1, 0, 0, 0); /* no position: held */
        assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
        assert_true(fabsf(pose.z - held) < 0.05f);
    }
    return pose;
}

/* A 0.4 cm deviation from the node's copies: the mesh's moves the position more than a face box's, and
 * the quality is the config's (position_r_scale), not the model's name. */
static void position_quality_per_model(float before)
{
    filter_node_t mesh = node, box = node;
    hkf_head_pose_measurement_t m = measurement(T0 + 32 * FRAME_US, 1, 0, 0, 0);
    hkf_head_pose_t pose;
    float mesh_step, box_step;
    m.model = "mesh_pnp";
    m.z = before + 0.4f, m.x = 2.0f, m.y = -1.0f;
    assert_int_equal(filter_node_measurement(&mesh, &m, &pose), 1);
    mesh_step = pose.z - before;
    m.model = "whenet"; /* a model change restarts the angles' track, not the position's */
    assert_int_equal(filter_node_measurement(&box, &m, &pose), 1);
    box_step = pose.z - before;
    print_message("a 0.4 cm deviation moves the position %.3f cm (mesh), %.3f cm (face box)\n", mesh_step, box_step);
    assert_true(mesh_step > 0.0f && box_step > 0.0f && box_step < 0.5f * mesh_step);
    {   /* whenet given the mesh's scale moves it as the mesh */
        node_config_t as_mesh = config;
        char error[200];
        box = node;
        box.config = &as_mesh;
        assert_int_equal(node_config_set(&as_mesh, "model.whenet.position_r_scale = 1", error, sizeof error), 0);
        /* the node resolves its models when it starts: this copy's are those of a node started with as_mesh */
        assert_int_equal(resolved_models_init(&box.models, &as_mesh), HKF_OK);
        assert_int_equal(filter_node_measurement(&box, &m, &pose), 1);
        assert_true(pose.z - before == mesh_step);
    }
}

/* A lean of 10 cm followed at once; RECENTER moves the centre there, RESET starts a new track and centre. */
static void position_lean_recenter_reset(void)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    hkf_tracker_command_t command = {0, HKF_TRACKER_COMMAND_T_RECENTER};
    m = measurement(T0 + 32 * FRAME_US, 1, 0, 0, 0);
    m.model = "mesh_pnp";
    m.z = 50.0f, m.x = 2.0f, m.y = -1.0f;
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    assert_true(pose.z < 59.0f); /* a lean of 10 cm: the motion detector follows at once */
    assert_int_equal(filter_node_command(&node, &command), 0);
    m = measurement(T0 + 33 * FRAME_US, 1, 0, 0, 0);
    m.model = "mesh_pnp";
    m.z = 50.0f, m.x = 2.0f, m.y = -1.0f;
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    assert_true(pose.position_center[2] < 59.0f); /* the centre moved to where the head was */
    command.command = HKF_TRACKER_COMMAND_T_RESET;
    assert_int_equal(filter_node_command(&node, &command), 0);
    m = measurement(T0 + 34 * FRAME_US, 1, 0, 0, 0);
    m.model = "mesh_pnp";
    m.z = 40.0f, m.x = 0.0f, m.y = 0.0f;
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    assert_true(pose.z == 40.0f && pose.position_center[2] == 40.0f); /* a new track, and centre */
}

static void test_position_filtered(void **state)
{
    const hkf_head_pose_t held = position_filtered_and_held();
    (void)state;
    position_quality_per_model(held.z);
    position_lean_recenter_reset();
}

/* The second model's positions: where the mesh measured none (a profile) WHENet's box position
 * of the frame stands in, moved onto the mesh's by their running difference (the box reads the
 * head 3 cm farther here): the position holds where the head is, then follows a lean; a second
 * measurement of a frame the mesh measured only teaches the offset. */
static void test_second_model_position(void **state)
{
    hkf_head_pose_measurement_t first, second;
    hkf_head_pose_t pose;
    int64_t utime = T0;
    int i;
    (void)state;
    for (i = 0; i < 90; ++i) { /* 0-29 both measure; 30-59 the mesh folds, the head still; 60-89 a lean to 50 cm */
        const float truth = i < 60 ? 60.0f : 50.0f;
        const float noise = i % 2 ? 0.2f : -0.2f;
        utime += FRAME_US;
        first = measurement(utime, i < 30, 0, i < 30 ? 5 : 70, 0);
        first.model = "mesh_pnp";
        if (i < 30) {
            first.x = 1.0f, first.y = -2.0f, first.z = truth + noise;
        }
        (void)filter_node_receive(&node, &first, utime, &pose);
        second = first;
        second.model = "whenet";
        second.valid = 1;
        second.yaw = i < 30 ? 5.0f : 70.0f;
        second.x = 1.5f, second.y = -2.0f, second.z = truth + 3.0f - noise;
        (void)filter_node_receive(&node, &second, utime + 1000, &pose);
        if (i == 29 || i == 59) {
            const int64_t at = node.position.utime;
            assert_true(filter_node_extrapolate(&node, utime + 2000, &pose) >= 0);
            print_message("frame %d: z %.2f cm (the head at %.0f cm; the last position taken at frame %lld)\n", i,
                          pose.z, truth, (long long)((at - T0) / FRAME_US - 1));
            assert_true(fabsf(pose.z - truth) < 0.5f && fabsf(pose.x - 1.0f) < 0.2f);
            assert_true(at == utime);
        }
    }
    assert_true(filter_node_extrapolate(&node, utime + 2000, &pose) >= 0);
    print_message("after the lean: z %.2f cm (the head at 50 cm)\n", pose.z);
    assert_true(fabsf(pose.z - 50.0f) < 1.0f);
}

/* A second model's position stands in only once the offset has averaged FILTER_NODE_POSITION_MIN_ALIGN
 * frames both measured: before, a frame the mesh missed keeps the position where the mesh left it. */
static void test_second_position_waits_for_the_offset(void **state)
{
    hkf_head_pose_t pose;
    int64_t utime = T0;
    int i;
    (void)state;
    for (i = 0; i < FILTER_NODE_POSITION_MIN_ALIGN; ++i) {
        int64_t taken;
        utime += FRAME_US;
        feed_two_models(utime, utime, 1.0f, 60.0f, i != FILTER_NODE_POSITION_MIN_ALIGN - 1, 3.0f, &pose);
        taken = node.position.utime;
        assert_true(node.position.offset.frames == (i < FILTER_NODE_POSITION_MIN_ALIGN - 1 ? i + 1 : i));
        assert_true(taken == (i < FILTER_NODE_POSITION_MIN_ALIGN - 1 ? utime : utime - FRAME_US)); /* not aligned yet */
    }
    utime += FRAME_US;
    feed_two_models(utime, utime, 1.0f, 60.0f, 1, 3.0f, &pose); /* the fifth frame both measured */
    utime += FRAME_US;
    feed_two_models(utime, utime, 1.0f, 60.0f, 0, 3.0f, &pose);
    assert_true(node.position.utime == utime); /* the second's stands in, moved onto the mesh's */
    assert_true(filter_node_extrapolate(&node, utime, &pose) == 1 && fabsf(pose.z - 60.0f) < 0.1f);
}

/* The position's offset is a model's own (mutant 14 of tests/mutation/mutants.txt). WHENet's box reads 10 cm
 * farther than the mesh and its offset is learnt; then another second model (a box that reads as the mesh does) arrives while the
 * mesh has folded. Its positions wait for an offset of their own (FILTER_NODE_POSITION_MIN_ALIGN frames
 * both measured) and are never moved 10 cm by WHENet's. */
static void second_model_frame(int64_t utime, char *second_model, int mesh_position, float second_z,
                               hkf_head_pose_t *pose)
{
    hkf_head_pose_measurement_t first = measurement(utime, 1, 0, 5, 0), second;
    hkf_head_pose_t ignored;
    first.model = "mesh_pnp";
    if (mesh_position) {
        first.x = 0.0f, first.y = 0.0f, first.z = 60.0f;
    }
    second = first;
    second.model = second_model;
    second.x = 0.0f, second.y = 0.0f, second.z = second_z;
    (void)filter_node_receive(&node, &first, utime, pose);
    (void)filter_node_receive(&node, &second, utime + 1000, &ignored);
}

static void test_position_offset_starts_over_for_another_second_model(void **state)
{
    hkf_head_pose_t pose;
    int64_t utime = T0;
    int i;
    (void)state;
    for (i = 0; i < 30; ++i) { /* both measure: WHENet's box 10 cm farther, the head at 60 cm */
        utime += FRAME_US;
        second_model_frame(utime, "whenet", 1, 70.0f, &pose);
    }
    assert_true(fabsf((float)node.position.offset.offset[2] + 10.0f) < 0.01f);
    {
        const int64_t taken_before = node.position.utime;
        utime += FRAME_US; /* the mesh folds; another second model, at the head's true 60 cm */
        second_model_frame(utime, "box_other", 0, 60.0f, &pose);
        assert_string_equal(node.position.offset.model, "box_other");
        assert_true(node.position.offset.frames == 0);
        assert_true(node.position.utime == taken_before); /* not aligned yet: its position waits */
        assert_true(filter_node_extrapolate(&node, utime, &pose) >= 0);
        print_message("another second model: z %.2f cm (the head at 60 cm; WHENet's offset would read 50)\n", pose.z);
        assert_true(fabsf(pose.z - 60.0f) < 0.5f);
    }
    for (i = 0; i < FILTER_NODE_POSITION_MIN_ALIGN; ++i) { /* both measure: the new model's own offset, 0 cm */
        utime += FRAME_US;
        second_model_frame(utime, "box_other", 1, 60.0f, &pose);
    }
    utime += FRAME_US;
    second_model_frame(utime, "box_other", 0, 60.0f, &pose);
    assert_true(node.position.utime == utime); /* aligned on its own frames: it stands in */
    assert_true(fabsf((float)node.position.offset.offset[2]) < 0.01f);
    assert_true(filter_node_extrapolate(&node, utime, &pose) == 1 && fabsf(pose.z - 60.0f) < 0.5f);
}

/* Hardening round 3, item 1: the mesh misses a frame, the clock steps back 1 h, and the second
 * model's measurement of the missed frame arrives after the node has followed the new clock.
 * Before, the position track took that old (1 h later) stamp and then froze for the hour; now
 * the resync forgets the kept frames and the position follows the head on the new clock. */
static void test_position_follows_after_clock_step_back(void **state)
{
    hkf_head_pose_measurement_t m, late;
    hkf_head_pose_t pose;
    const int64_t back = 3600000000LL;
    int i;
    (void)state;
    for (i = 0; i < 20; ++i) {
        feed_two_models(T0 + i * FRAME_US, T0 + i * FRAME_US, 0.0f, 60.0f, 1, 2.0f, &pose);
    }
    m = measurement(T0 + 20 * FRAME_US, 1, 0, 5, 0); /* frame 20: the mesh finds no position */
    m.model = "mesh_pnp";
    (void)filter_node_receive(&node, &m, m.utime, &pose);
    late = m;
    late.model = "whenet";
    late.x = 0.0f, late.y = 0.0f, late.z = 62.0f;
    for (i = 21; i < 21 + STREAM_RESYNC_MESSAGES; ++i) { /* the clock steps back 1 h: followed */
        m = measurement(T0 + i * FRAME_US - back, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        m.x = 0.0f, m.y = 0.0f, m.z = 60.0f;
        (void)filter_node_receive(&node, &m, m.utime, &pose);
    }
    assert_int_equal(node.counts.clock_resyncs, 1);
    (void)filter_node_receive(&node, &late, T0 + i * FRAME_US - back + 2000, &pose); /* frame 20's second, late */
    for (; i < 60; ++i) { /* a steady move in x: 0.5 cm a frame */
        const float x = 0.5f * (float)(i - 20);
        m = measurement(T0 + i * FRAME_US - back, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        m.x = x, m.y = 0.0f, m.z = 60.0f;
        assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
    }
    print_message("after the clock step: x %.2f cm (the head at %.1f cm)\n", pose.x, 0.5 * (59 - 20));
    assert_true(fabsf(pose.x - 0.5f * (59 - 20)) < 1.0f);
    assert_true(pose.x_rate > 10.0f); /* 15 cm/s */
}

/* Hardening round 4, item 6: the position started while the angles had not (a restart after a gap,
 * a frame without a face, then a second model's measurement of it with NaN angles but a valid
 * position), and then the clock stepped back 1 h. The resync restarted only a started angle track,
 * so the position kept its stamp on the old clock and refused every later one: x stayed at 30 cm
 * while the mesh measured 0 -> 32 cm (here 0 -> -29 cm). Now the position restarts with the clock and follows,
 * and the resync forgets the kept frames: the old frame's second measurement, sent again after it, is
 * not taken on its old stamp. */
static void test_position_alone_follows_a_clock_step(void **state)
{
    hkf_head_pose_measurement_t m, second;
    hkf_head_pose_t pose;
    const int64_t back = 3600000000LL, gap = (int64_t)(2e6 * (double)config.settings.max_dt);
    int i;
    (void)state;
    for (i = 0; i < 20; ++i) { /* both models, the box 0 cm off the mesh, at x 30 cm */
        feed_two_models(T0 + i * FRAME_US, T0 + i * FRAME_US, 30.0f, 60.0f, 1, 0.0f, &pose);
    }
    m = measurement(T0 + i * FRAME_US + gap, 0, 0, 0, 0); /* after a gap: no face; the track restarts */
    m.model = "mesh_pnp";
    assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 0);
    assert_int_equal(hkf_get_status(&node.filter), HKF_STATUS_UNINITIALIZED);
    second = m; /* the second model's measurement of that frame: NaN angles, a valid position */
    second.model = "whenet";
    second.valid = 1;
    second.pitch = second.yaw = second.roll = NAN;
    second.x = 30.0f, second.y = 0.0f, second.z = 60.0f;
    assert_int_equal(filter_node_receive(&node, &second, m.utime + 1000, &pose), 0);
    assert_true(hkf_position_started(&node.position.filter)); /* the position alone has started */
    for (++i; i < 80; ++i) { /* the clock steps back 1 h; the mesh measures x 0 -> -29 cm */
        const float x = -0.5f * (float)(i - 21);
        m = measurement(T0 + i * FRAME_US + gap - back, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        m.x = x, m.y = 0.0f, m.z = 60.0f;
        (void)filter_node_receive(&node, &m, T0 + i * FRAME_US + gap, &pose);
        if (i == 21 + STREAM_RESYNC_MESSAGES) { /* the new clock followed: the old frame's second again, late */
            hkf_head_pose_t ignored;
            assert_int_equal(node.counts.clock_resyncs, 1);
            (void)filter_node_receive(&node, &second, T0 + i * FRAME_US + gap + 1000, &ignored);
        }
    }
    assert_int_equal(node.counts.clock_resyncs, 1);
    print_message("the clock stepped back with the position alone started: x %.2f cm (the head at %.1f cm)\n",
                  pose.x, -0.5 * (79 - 21));
    assert_true(pose.utime == m.utime);
    assert_true(fabsf(pose.x + 0.5f * (79 - 21)) < 1.0f);
}

/* Round 4, moderate item 1: a forged frame with the next seq, stamped 0.7 s ahead (past the
 * position's max_dt 0.5 s, inside the 5 s clock rule), was published as x 1000, y -1000, z 1000,
 * TRACKING: a first position after a gap went ungated. Now it is gated against the held track. */
static void test_forged_position_after_a_gap_gated(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    const int64_t ahead = 700000;
    int i;
    (void)state;
    assert_true(ahead > (int64_t)(1e6 * (double)config.position.max_dt) && ahead < STREAM_CLOCK_JUMP_US);
    for (i = 0; i < 30; ++i) {
        m = measurement(T0 + i * FRAME_US, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        m.x = 2.0f, m.y = 1.0f, m.z = 60.0f;
        assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
    }
    m = measurement(T0 + 29 * FRAME_US + ahead, 1, 0, 5, 0); /* the forged frame: the next seq */
    m.model = "mesh_pnp";
    m.x = 1000.0f, m.y = -1000.0f, m.z = 1000.0f;
    assert_int_equal(filter_node_receive(&node, &m, T0 + 29 * FRAME_US + 1000, &pose), 1);
    print_message("a forged position 0.7 s ahead: published (%.2f, %.2f, %.2f)\n", pose.x, pose.y, pose.z);
    assert_true(fabsf(pose.x - 2.0f) < 0.5f && fabsf(pose.y - 1.0f) < 0.5f && fabsf(pose.z - 60.0f) < 0.5f);
    assert_int_equal(node.counts.positions_gated, 1);
}

/* Round 4, moderate item 3: RECENTER while the position coasts toward the camera. The coast went
 * below z = 0 in libhkf while the pose showed FILTER_NODE_MIN_Z, and the centre was set on the
 * former (z -43.9): hkf-opentrack then sent TZ +44.9 cm right after RECENTER. Now the centre is
 * the position as published, and the pose right after reads 0 from it. */
static void test_recenter_during_a_coast_toward_the_camera(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    hkf_tracker_command_t command = {0, HKF_TRACKER_COMMAND_T_RECENTER};
    int i;
    (void)state;
    for (i = 0; i < 30; ++i) { /* toward the camera at 60 cm/s, to 2 cm */
        m = measurement(T0 + i * FRAME_US, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        m.x = 0.0f, m.y = 0.0f, m.z = 2.0f + 2.0f * (float)(29 - i);
        assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
    }
    for (; i < 45; ++i) { /* the positions stop, the angles go on: the position coasts on toward the camera */
        m = measurement(T0 + i * FRAME_US, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
    }
    assert_true(pose.z == FILTER_NODE_MIN_Z);
    assert_int_equal(filter_node_command(&node, &command), 0);
    m = measurement(T0 + i * FRAME_US, 1, 0, 5, 0);
    m.model = "mesh_pnp";
    assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
    print_message("RECENTER during a coast toward the camera: centre z %.2f cm, z %.2f cm\n", pose.position_center[2],
                  pose.z);
    assert_true(pose.position_center[2] >= FILTER_NODE_MIN_Z);
    assert_true(fabsf(pose.z - pose.position_center[2]) < 1e-4f && fabsf(pose.x - pose.position_center[0]) < 1e-4f);
}

/* Item 5: positions far off, once or for long, never publish a position beyond the range the
 * node accepts, nor z below FILTER_NODE_MIN_Z; one forged message is refused by the gate; bad
 * positions (NaN, inf, z < 0, beyond 1000 cm) are counted and change nothing. */
static void test_position_gated_and_bounded(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    const float bad[][3] = {{NAN, 0, 60}, {0, INFINITY, 60}, {0, 0, -4.65f}, {1001, 0, 60}, {0, 0, 0.5f}};
    int i, frame = 0;
    (void)state;
    for (i = 0; i < 30; ++i, ++frame) { /* a still head at 60 cm */
        m = measurement(T0 + frame * FRAME_US, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        m.x = 1.0f + (i % 2 ? 0.05f : -0.05f), m.y = 0.0f, m.z = 60.0f;
        assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    }
    m = measurement(T0 + frame++ * FRAME_US, 1, 0, 5, 0); /* one forged message */
    m.model = "mesh_pnp";
    m.x = 1000.0f, m.y = -1000.0f, m.z = 1000.0f;
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    print_message("a forged (1000, -1000, 1000): published (%.2f, %.2f, %.2f)\n", pose.x, pose.y, pose.z);
    assert_true(fabsf(pose.x - 1.0f) < 0.5f && fabsf(pose.z - 60.0f) < 0.5f);
    assert_int_equal(node.counts.positions_gated, 1);
    for (i = 0; i < (int)(sizeof bad / sizeof bad[0]); ++i, ++frame) {
        m = measurement(T0 + frame * FRAME_US, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        m.x = bad[i][0], m.y = bad[i][1], m.z = bad[i][2];
        assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
        assert_true(fabsf(pose.x - 1.0f) < 0.5f && fabsf(pose.z - 60.0f) < 0.5f);
    }
    assert_int_equal(node.counts.bad_positions, sizeof bad / sizeof bad[0]);
    /* x -1000 cm for 10 frames, +1000 once, then frames without a position for 3 s */
    for (i = 0; i < 100; ++i, ++frame) {
        m = measurement(T0 + frame * FRAME_US, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        if (i <= 10) {
            m.x = i < 10 ? -1000.0f : 1000.0f, m.y = 0.0f, m.z = i < 10 ? 2.0f : 1000.0f;
        }
        assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
        assert_true(isfinite(pose.x) && fabsf(pose.x) <= HKF_MAX_ABS_POSITION && fabsf(pose.y) <= HKF_MAX_ABS_POSITION);
        assert_true(pose.z >= FILTER_NODE_MIN_Z && pose.z <= HKF_MAX_ABS_POSITION);
    }
    print_message("after -1000 x 10, +1000 once, 3 s without: x %.1f cm, z %.1f cm\n", pose.x, pose.z);
    for (i = 0; i < 60; ++i, ++frame) { /* toward the camera at 60 cm/s to 2 cm, then no position: the coast stops at 1 cm */
        m = measurement(T0 + frame * FRAME_US, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        if (i < 30) {
            m.x = 0.0f, m.y = 0.0f, m.z = 2.0f + 2.0f * (float)(29 - i);
        }
        assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
        assert_true(pose.z >= FILTER_NODE_MIN_Z && pose.z <= HKF_MAX_ABS_POSITION);
    }
    assert_true(pose.z == FILTER_NODE_MIN_Z);
}

/* Item 6: a head leaning at 15 cm/s whose positions stop while the angles go on. The position
 * coasts for the position's max_dt, then is held there with rate 0 (no jump back when the angles
 * are LOST), its variance growing; a RECENTER during the hold centres on what was published;
 * positions that resume where the head is do not jump. */
static void test_position_coast_bounded(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose, held;
    hkf_tracker_command_t command = {0, HKF_TRACKER_COMMAND_T_RECENTER};
    const double max_dt = (double)config.position.max_dt;
    const int64_t coast_us = (int64_t)(1e6 * (double)config.settings.coast_time);
    float last_variance = 0.0f, last_measured = 0.0f, rate;
    int i;
    (void)state;
    for (i = 0; i < 60; ++i) {
        m = measurement(T0 + i * FRAME_US, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        m.x = last_measured = 15.0f * (float)(i * FRAME_US * 1e-6), m.y = 0.0f, m.z = 60.0f;
        assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
    }
    print_message("leaning at 15 cm/s: x %.2f cm (measured %.2f), rate %.2f cm/s\n", pose.x, last_measured, pose.x_rate);
    assert_int_equal(pose.position_status, HKF_HEAD_POSE_T_TRACKING); /* measured in this frame */
    assert_true(pose.x_rate > 5.0f);
    rate = pose.x_rate;
    for (; i < 150; ++i) { /* 3 s of angles without a position */
        const double since = (double)(i - 59) * FRAME_US * 1e-6;
        m = measurement(T0 + i * FRAME_US, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
        assert_true(pose.x <= last_measured + rate * (float)max_dt + 0.1f); /* at most max_dt of coast */
        assert_true(pose.position_variance[0] > last_variance); /* growing */
        last_variance = pose.position_variance[0];
        if (since > max_dt) {
            assert_true(pose.x_rate == 0.0f);
            assert_int_equal(pose.position_status, HKF_HEAD_POSE_T_LOST); /* stale: held */
        } else if (since < max_dt) {
            assert_int_equal(pose.position_status, HKF_HEAD_POSE_T_COASTING); /* round 4: the message says so */
        }
    }
    held = pose;
    print_message("held at x %.2f cm (last measured %.2f), variance %.3f cm^2, rate %.1f\n", held.x, last_measured,
                  held.position_variance[0], held.x_rate);
    assert_int_equal(filter_node_silence(&node, m.utime + coast_us, &pose), 1); /* the angles fall silent */
    assert_int_equal(pose.status, HKF_HEAD_POSE_T_LOST);
    assert_true(pose.x == held.x); /* no jump at LOST */
    assert_int_equal(filter_node_command(&node, &command), 0);
    m = measurement(T0 + i * FRAME_US, 1, 0, 5, 0);
    m.model = "mesh_pnp";
    assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
    assert_true(fabsf(pose.x - pose.position_center[0]) < 1e-4f); /* TX 0 after RECENTER */
    ++i;
    m = measurement(T0 + i * FRAME_US, 1, 0, 5, 0); /* positions resume where the head is held */
    m.model = "mesh_pnp";
    m.x = held.x, m.y = 0.0f, m.z = 60.0f;
    assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
    assert_true(fabsf(pose.x - held.x) < 0.01f && fabsf(pose.x - pose.position_center[0]) < 0.01f);
}

/* Item 7: RESET forgets the second model's position offset with the rest: after it, the box
 * positions (10 cm farther than the mesh's before) are not moved by the old offset. */
static void test_reset_forgets_second_offset(void **state)
{
    hkf_head_pose_t pose;
    hkf_tracker_command_t command = {0, HKF_TRACKER_COMMAND_T_RESET};
    int i;
    (void)state;
    for (i = 0; i < 30; ++i) { /* both measure: the box reads 10 cm farther */
        feed_two_models(T0 + i * FRAME_US, T0 + i * FRAME_US, 0.0f, 60.0f, 1, 10.0f, &pose);
    }
    assert_int_equal(filter_node_command(&node, &command), 0);
    for (; i < 60; ++i) { /* after RESET the mesh folds; the box alone, not yet aligned, with a new person at 70 cm */
        feed_two_models(T0 + i * FRAME_US, T0 + i * FRAME_US, 0.0f, 70.0f, 0, 0.0f, &pose);
        assert_true(pose.z == 0.0f || fabsf(pose.z - 70.0f) < 1.0f); /* never moved 10 cm by the old offset */
    }
    for (; i < 70; ++i) { /* the mesh back: the offset learnt anew (0 cm) */
        feed_two_models(T0 + i * FRAME_US, T0 + i * FRAME_US, 0.0f, 70.0f, 1, 0.0f, &pose);
    }
    for (; i < 80; ++i) {
        feed_two_models(T0 + i * FRAME_US, T0 + i * FRAME_US, 0.0f, 70.0f, 0, 0.0f, &pose);
        assert_true(fabsf(pose.z - 70.0f) < 1.0f);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_position_filtered, setup),
        cmocka_unit_test_setup(test_second_model_position, setup),
        cmocka_unit_test_setup(test_second_position_waits_for_the_offset, setup),
        cmocka_unit_test_setup(test_position_follows_after_clock_step_back, setup),
        cmocka_unit_test_setup(test_position_alone_follows_a_clock_step, setup),
        cmocka_unit_test_setup(test_position_gated_and_bounded, setup),
        cmocka_unit_test_setup(test_forged_position_after_a_gap_gated, setup),
        cmocka_unit_test_setup(test_recenter_during_a_coast_toward_the_camera, setup),
        cmocka_unit_test_setup(test_position_coast_bounded, setup),
        cmocka_unit_test_setup(test_reset_forgets_second_offset, setup),
        cmocka_unit_test_setup(test_position_offset_starts_over_for_another_second_model, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
