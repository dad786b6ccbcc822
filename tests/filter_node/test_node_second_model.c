/*
 * test_node_second_model.c - hkf-filter's node (filter_node/filter_node.c), a second model on the channel: its measurement fused into its frame, late or repeated ones, alone, its offset, and another publisher's model.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "node_test_support.h"

/* RECENTER forgets the kept frames: a second model's measurement of a frame
 * from before the command is not fused (it would redo frames on the old
 * centre) but counted. */
static void test_second_model_after_recenter(void **state)
{
    hkf_head_pose_measurement_t m, second;
    hkf_head_pose_t pose;
    hkf_tracker_command_t command;
    int i;
    (void)state;
    for (i = 0; i < 5; ++i) {
        m = measurement(T0 + i * FRAME_US, 1, 0, 5, 0);
        assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
    }
    second = m;
    second.model = "hopenet";
    command.utime = 0;
    command.command = HKF_TRACKER_COMMAND_T_RECENTER;
    assert_int_equal(filter_node_command(&node, &command), 0);
    assert_int_equal(filter_node_receive(&node, &second, m.utime + 10000, &pose), 0);
    assert_int_equal(node.counts.paired, 0);
    assert_int_equal(node.counts.unpaired, 1);
}

static void test_second_model_fused_into_its_frame(void **state)
{
    enum { FRAMES = 300, LATE = 3 };
    static hkf_head_pose_measurement_t first[FRAMES], second[FRAMES];
    hkf_filter_t reference, before;
    hkf_output_t ours, theirs;
    int known1, known2, i, a, published = 0, published_second = 0, second_only; /* frames only the second model measured */
    const hkf_settings_t s1 = node_config_for_model(&config, "fsanet", &known1);
    const hkf_settings_t hopenet = node_config_for_model(&config, "hopenet", &known2);
    const hkf_model_noise_t s2 = hkf_model_noise_of(&hopenet);
    (void)state;
    config.second_alone_from_yaw = 180; /* the rule for large turns is another test's: fused on every frame */
    assert_int_equal(filter_node_init(&node, &config), HKF_OK); /* the node resolves its config at start */
    node.second.align_frames = 0; /* and so is the models' offset */
    assert_true(known1 && known2);
    assert_int_equal(hkf_init(&reference, &s1), HKF_OK);
    second_only = make_pair_frames(first, second, FRAMES, &reference, &s2);
    for (i = 0; i < FRAMES + LATE; ++i) {
        hkf_head_pose_t pose;
        if (i < FRAMES) {
            published += filter_node_receive(&node, &first[i], first[i].utime + 2000, &pose);
        }
        if (i >= LATE) {
            hkf_output_t now;
            memcpy(&before, &node.filter, sizeof before);
            /* published only for the newest frame where the first model found no face (its pose was a
             * prediction); elsewhere the frame's pose is out and the correction goes with the next frame's */
            const int alone = i - LATE == FRAMES - 1 && !first[i - LATE].valid;
            assert_int_equal(filter_node_receive(&node, &second[i - LATE], first[i - LATE].utime + 40000, &pose), alone);
            assert_true(memcmp(&before, &node.filter, sizeof before) != 0); /* taken */
            assert_int_equal(hkf_get_output(&node.filter, &now), HKF_OK);
            assert_true(!alone || (pose.utime == first[FRAMES - 1].utime && pose.yaw == (float)now.angle[1]));
            published_second += alone;
        }
    }
    assert_true(second_only > 20);
    /* every frame once a track exists: from the first model's first face, or the
     * second model's of frame 0, fused when frame LATE has come */
    for (i = 0; i < FRAMES && !first[i].valid; ++i) {
    }
    assert_int_equal(published, FRAMES - (i < LATE + 1 ? i : LATE + 1));
    assert_int_equal(published_second, !first[FRAMES - 1].valid);
    assert_int_equal(node.counts.paired, FRAMES);
    assert_int_equal(node.counts.unpaired, 0);
    assert_int_equal(node.counts.received, 2 * FRAMES); /* each model's, each counted once */
    assert_int_equal(node.counts.other_publisher, 0);
    assert_int_equal(node.counts.unknown_models, 0);
    assert_int_equal(hkf_get_output(&node.filter, &ours), HKF_OK);
    assert_int_equal(hkf_get_output(&reference, &theirs), HKF_OK);
    for (a = 0; a < 3; ++a) {
        assert_float_equal(ours.angle[a], theirs.angle[a], 1e-4);
        assert_float_equal(ours.variance[a], theirs.variance[a], 1e-6);
    }
}

/* A second measurement is used once per frame, only with a face, and only
 * while its frame is kept: otherwise it is counted and changes nothing. */
static void test_second_model_late_or_repeated_not_used(void **state)
{
    hkf_head_pose_measurement_t m[40], other;
    hkf_head_pose_t pose;
    hkf_filter_t before;
    int i;
    (void)state;
    for (i = 0; i < 40; ++i) {
        m[i] = measurement(T0 + i * FRAME_US, 1, 1.0, 10.0, -2.0);
        assert_int_equal(filter_node_receive(&node, &m[i], m[i].utime + 2000, &pose), 1);
    }
    memcpy(&before, &node.filter, sizeof before);
    other = m[39 - FILTER_NODE_PAIR_FRAMES]; /* just older than the kept frames */
    other.model = "hopenet";
    other.yaw = 30.0f;
    assert_int_equal(filter_node_receive(&node, &other, T0 + 40 * FRAME_US, &pose), 0);
    other = m[35];
    other.model = "hopenet";
    other.valid = 0; /* no face: nothing to add */
    assert_int_equal(filter_node_receive(&node, &other, T0 + 40 * FRAME_US, &pose), 0);
    other.valid = 1;
    other.yaw = NAN;
    assert_int_equal(filter_node_receive(&node, &other, T0 + 40 * FRAME_US, &pose), 0);
    assert_memory_equal(&before, &node.filter, sizeof before);
    other.yaw = 12.0f;
    /* taken, not published: frame 35's pose is out, and the correction goes with the next frame's */
    assert_int_equal(filter_node_receive(&node, &other, T0 + 40 * FRAME_US, &pose), 0);
    assert_true(memcmp(&before, &node.filter, sizeof before) != 0);
    memcpy(&before, &node.filter, sizeof before);
    other.yaw = 14.0f; /* the same frame's second again */
    assert_int_equal(filter_node_receive(&node, &other, T0 + 40 * FRAME_US, &pose), 0);
    assert_memory_equal(&before, &node.filter, sizeof before);
    assert_int_equal(node.counts.paired, 1);
    assert_int_equal(node.counts.unpaired, 3);
    assert_int_equal(node.counts.bad_values, 1);
    assert_int_equal(node.counts.other_publisher, 0);
    assert_int_equal(node.counts.restarts, 0);
    /* the next frame's pose follows; the model table is not switched */
    m[0] = measurement(T0 + 40 * FRAME_US, 1, 1.0, 10.0, -2.0);
    m[0].seq = m[39].seq + 1;
    assert_int_equal(filter_node_receive(&node, &m[0], m[0].utime + 2000, &pose), 1);
    assert_string_equal(node.model, "fsanet");
}

/* A face only the second model sees (a profile the mesh gives up on): the
 * track starts from it, and the first model's empty frames wait for its answers
 * (at 70 deg a frame takes the second's alone): each frame's one pose is its answer's. */
static void test_second_model_alone_starts_and_keeps_track(void **state)
{
    hkf_head_pose_measurement_t m, second;
    hkf_head_pose_t pose;
    int i, published = 0;
    (void)state;
    for (i = 0; i < 30; ++i) {
        m = measurement(T0 + i * FRAME_US, 0, 0, 0, 0);
        published += filter_node_receive(&node, &m, m.utime + 2000, &pose);
        second = m;
        second.model = "hopenet";
        second.valid = 1;
        second.pitch = -5.0f;
        second.yaw = 70.0f;
        second.roll = 3.0f;
        assert_int_equal(filter_node_receive(&node, &second, m.utime + 30000, &pose), 1);
        assert_true(fabsf(pose.yaw - 70.0f) < 1.0f && pose.status == HKF_HEAD_POSE_T_TRACKING);
    }
    assert_int_equal(published, 0);
    assert_int_equal(node.counts.awaited, 29);
    assert_int_equal(node.counts.paired, 30);
    assert_string_equal(node.model, "fsanet");
}

/* Two models that disagree by a steady offset (the second reads pitch 4 deg
 * higher, yaw 3 deg lower): the second is moved onto the first's frame, so the
 * fused track keeps to where the first model alone puts it (on average over
 * the second half; the lag differs, as fusing halves R) - without the
 * alignment it sits between the two. */
static void test_second_model_offset_aligned(void **state)
{
    hkf_head_pose_measurement_t m, second;
    hkf_head_pose_t pose;
    filter_node_t alone, unaligned;
    double bias_aligned[2] = {0, 0}, bias_unaligned[2] = {0, 0};
    int i;
    (void)state;
    assert_int_equal(filter_node_init(&alone, &config), 0);
    assert_int_equal(filter_node_init(&unaligned, &config), 0);
    unaligned.second.align_frames = 0;
    for (i = 0; i < 400; ++i) {
        hkf_head_pose_t p_alone, p_unaligned;
        const double pitch = 5.0 * sin(0.05 * i), yaw = 20.0 * sin(0.03 * i), noise = 0.5 * sin(1.7 * i),
                     noise2 = 0.5 * sin(2.3 * i + 1.0); /* the models' errors are their own */
        m = measurement(T0 + i * FRAME_US, 1, pitch + noise, yaw - noise, 1.0);
        second = m;
        second.model = "hopenet";
        second.pitch = (float)(pitch + 4.0 + noise2);
        second.yaw = (float)(yaw - 3.0 - noise2);
        assert_int_equal(filter_node_receive(&node, &m, m.utime + 2000, &pose), 1);
        assert_int_equal(filter_node_receive(&alone, &m, m.utime + 2000, &p_alone), 1);
        assert_int_equal(filter_node_receive(&unaligned, &m, m.utime + 2000, &p_unaligned), 1);
        assert_int_equal(filter_node_receive(&node, &second, m.utime + 30000, &pose), 0); /* folded into the next */
        assert_int_equal(filter_node_receive(&unaligned, &second, m.utime + 30000, &p_unaligned), 0);
        if (i >= 200) {
            bias_aligned[0] += (pose.pitch - p_alone.pitch) / 200.0;
            bias_aligned[1] += (pose.yaw - p_alone.yaw) / 200.0;
            bias_unaligned[0] += (p_unaligned.pitch - p_alone.pitch) / 200.0;
            bias_unaligned[1] += (p_unaligned.yaw - p_alone.yaw) / 200.0;
        }
    }
    print_message("mean offset from the first model's track, pitch / yaw: aligned %.3f / %.3f deg, unaligned "
                  "%.3f / %.3f deg\n", bias_aligned[0], bias_aligned[1], bias_unaligned[0], bias_unaligned[1]);
    assert_true(fabs(bias_aligned[0]) < 0.1 && fabs(bias_aligned[1]) < 0.1);
    /* unaligned, the second model pulls the track by its weight, R1 / (R1 + R2) of its offset: in pitch it is
     * visible (0.23 deg of 4 with the defaults); in yaw hopenet's curve leaves it next to none */
    assert_true(bias_unaligned[0] > 0.15 && bias_unaligned[0] > 5.0 * fabs(bias_aligned[0]));
    /* the curve at the second's angles: its pitch 4 deg high, its yaw 3 deg low, wherever it looked (within
     * its sway: at the sway's ends the fit also sees the second's own noise, in its angle and, against it, in
     * the difference) */
    for (i = -16; i <= 16; i += 4) {
        assert_float_equal(model_alignment_correction(&node.second.alignment, 0, 0.25 * i + 4.0), -4.0, 0.1);
        assert_float_equal(model_alignment_correction(&node.second.alignment, 1, i - 3.0), 3.0, 0.1);
    }
}

/* The curve is fitted from the first frame on: after 10 frames that both models measured 4 deg apart in
 * pitch (and 3 in yaw), the node has learnt 4 (and -3), not a fraction of it on its way to the window, and
 * beyond what it saw it keeps that. A large turn teaches the curve where the second model looked, and only
 * there: the second's pitch of -20 deg learns 22 deg, its pitch of 2-5 deg keeps 4 (the knot between
 * follows the two). */
static void test_second_model_offset_from_the_first_frames(void **state)
{
    hkf_head_pose_measurement_t m, second;
    hkf_head_pose_t pose;
    const model_alignment_t *curve = &node.second.alignment;
    int i;
    (void)state;
    for (i = 0; i < 10; ++i) {
        m = measurement(T0 + i * FRAME_US, 1, 6.0 + 0.3 * i, 5.0, 0.0);
        second = m;
        second.model = "hopenet";
        second.pitch = m.pitch - 4.0f;
        second.yaw = m.yaw + 3.0f;
        assert_int_equal(filter_node_receive(&node, &m, m.utime + 2000, &pose), 1);
        assert_int_equal(filter_node_receive(&node, &second, m.utime + 20000, &pose), 0); /* folded into the next */
    }
    assert_int_equal(curve->frames, 10);
    assert_float_equal(model_alignment_correction(curve, 0, 0.0), 4.0, 1e-4);
    assert_float_equal(model_alignment_correction(curve, 0, -30.0), 4.0, 1e-4); /* beyond what it saw: the nearest */
    assert_float_equal(model_alignment_correction(curve, 1, 8.0), -3.0, 1e-4);
    /* at a large turn (the first model's |yaw| >= 25 deg) the curve learns there too */
    for (i = 10; i < 40; ++i) {
        m = measurement(T0 + i * FRAME_US, 1, 2.0, 40.0, 0.0);
        second = m;
        second.model = "hopenet";
        second.pitch = m.pitch - 12.0f;
        (void)filter_node_receive(&node, &m, m.utime + 2000, &pose);
        (void)filter_node_receive(&node, &second, m.utime + 20000, &pose);
    }
    assert_int_equal(curve->frames, 40);
    assert_float_equal(model_alignment_correction(curve, 0, -10.0), 12.0, 0.05);
    /* within 0.3: the smoothing (MODEL_ALIGNMENT_SMOOTHING, 0.1 of a frame's weight per squared step) pulls a
     * knot that ten frames taught a little toward the 8 deg steeper knot beside it */
    assert_float_equal(model_alignment_correction(curve, 0, 3.0), 4.0, 0.3);
    assert_float_equal(model_alignment_correction(curve, 1, 8.0), -3.0, 0.05);
    /* another second model: its own curve, from its first frame on */
    m = measurement(T0 + 40 * FRAME_US, 1, 2.0, 5.0, 0.0);
    second = m;
    second.model = "whenet";
    second.pitch = m.pitch + 1.0f;
    (void)filter_node_receive(&node, &m, m.utime + 2000, &pose);
    (void)filter_node_receive(&node, &second, m.utime + 20000, &pose);
    assert_int_equal(curve->frames, 1);
    assert_float_equal(model_alignment_correction(curve, 0, 3.0), -1.0, 1e-4);
    assert_float_equal(model_alignment_correction(curve, 0, -10.0), -1.0, 1e-4);
}

/* Both models near the yaw seam (WHENet reports up to +-180): the head sways
 * across it and the second model reads 2 deg further right, so their
 * difference is -2 deg, whichever side of the seam each reading falls on. The
 * offset learnt is -2 (not a mean of -2 and 358), and the fused yaw stays
 * with the first model's, across the seam. */
static void test_second_model_offset_across_the_seam(void **state)
{
    hkf_head_pose_measurement_t m, second;
    hkf_head_pose_t pose, first_alone;
    filter_node_t alone;
    double worst = 0.0;
    int i;
    (void)state;
    config.second_alone_from_yaw = 180; /* fused at every yaw: the offset is learnt at the seam too */
    assert_int_equal(filter_node_init(&node, &config), 0);
    assert_int_equal(filter_node_init(&alone, &config), 0);
    for (i = 0; i < 120; ++i) {
        const double yaw = 179.0 + 2.0 * sin(0.2 * i); /* 177 .. 181 deg, i.e. across +-180 */
        m = measurement(T0 + i * FRAME_US, 1, 0.0, yaw >= 180.0 ? yaw - 360.0 : yaw, 0.0);
        second = m;
        second.model = "hopenet";
        second.yaw = (float)(yaw + 2.0 >= 180.0 ? yaw + 2.0 - 360.0 : yaw + 2.0);
        assert_int_equal(filter_node_receive(&node, &m, m.utime + 2000, &pose), 1);
        assert_int_equal(filter_node_receive(&alone, &m, m.utime + 2000, &first_alone), 1);
        assert_int_equal(filter_node_receive(&node, &second, m.utime + 20000, &pose), 0); /* folded into the next */
        if (i >= 20) {
            const double d = fabs(fmod(pose.yaw - first_alone.yaw + 540.0, 360.0) - 180.0);
            worst = d > worst ? d : worst;
        }
    }
    assert_float_equal(model_alignment_correction(&node.second.alignment, 1, 179.0), -2.0, 1e-3);
    assert_float_equal(model_alignment_correction(&node.second.alignment, 1, -179.0), -2.0, 1e-3);
    print_message("largest distance from the first model's track: %.3f deg\n", worst);
    /* the fused track stays with the first model's: a seam error would put it 2 deg (the offset) or a turn
     * away; what remains is the dynamics of a halved R (0.59 deg on this noise-free turn) */
    assert_true(worst < 1.0);
}

/* Where the first model measures a large turn (|yaw| >= pair_second_alone_from_yaw,
 * 25 deg), a frame the second model also measured takes the second's
 * measurement alone, with its own R; below, both are fused. The node's track
 * is libhkf's stepped that way. */
static void test_second_model_alone_at_large_yaw(void **state)
{
    hkf_head_pose_measurement_t m, second;
    hkf_head_pose_t pose;
    hkf_filter_t reference;
    hkf_calibration_t calibration;
    hkf_output_t ours, theirs;
    int known, i, a;
    const hkf_settings_t s1 = node_config_for_model(&config, "fsanet", &known);
    const hkf_settings_t hopenet = node_config_for_model(&config, "hopenet", &known);
    const hkf_model_noise_t s2 = hkf_model_noise_of(&hopenet);
    (void)state;
    node.second.align_frames = 0;
    assert_float_equal(config.second_alone_from_yaw, 25.0, 0.0);
    assert_int_equal(hkf_init(&reference, &s1), HKF_OK);
    assert_int_equal(hkf_calibration_init(&calibration, &config.calibration, &reference), HKF_OK);
    for (i = 0; i < 60; ++i) {
        const double yaw = 1.5 * i; /* 0 .. 88.5 deg: fused below 25, the second alone from there */
        const hkf_real_t z[3] = {(hkf_real_t)(2.0 + 0.3 * sin(i)), (hkf_real_t)yaw, -1.0f};
        const hkf_real_t z2[3] = {(hkf_real_t)(-1.0 + 0.4 * cos(i)), (hkf_real_t)(yaw + 4.0), 2.0f};
        m = measurement(T0 + i * FRAME_US, 1, z[0], z[1], z[2]);
        second = m;
        second.model = "hopenet";
        second.pitch = z2[0];
        second.yaw = z2[1];
        second.roll = z2[2];
        /* below 25 deg the frame's pose goes out with the first's measurement, the second's folded into the
         * next; from there the first's waits for the second's, and the frame's pose goes out with that */
        assert_int_equal(filter_node_receive(&node, &m, m.utime + 2000, &pose), yaw < 25.0);
        assert_int_equal(filter_node_receive(&node, &second, m.utime + 30000, &pose), yaw >= 25.0);
        assert_int_equal(hkf_update_pair(&reference, yaw >= 25.0 ? NULL : z, z2, &s2,
                                         (hkf_real_t)(i == 0 ? 0.0 : FRAME_US * 1e-6), NULL), HKF_OK);
        assert_int_equal(hkf_calibration_update(&calibration, &reference, yaw >= 25.0 ? z2 : z,
                                                (hkf_real_t)(i == 0 ? 0.0 : FRAME_US * 1e-6)), HKF_OK);
    }
    assert_int_equal(hkf_get_output(&node.filter, &ours), HKF_OK);
    assert_int_equal(hkf_get_output(&reference, &theirs), HKF_OK);
    for (a = 0; a < 3; ++a) {
        assert_float_equal(ours.angle[a], theirs.angle[a], 1e-4);
    }
    /* the second model's pitch, not a blend: the first's (2 deg) is set aside */
    assert_true(fabs(ours.angle[0] - (-1.0)) < 1.0);
    assert_int_equal(node.counts.paired, 60);
    assert_int_equal(node.counts.awaited, 43); /* 25.5 .. 88.5 deg */
}

/* Another estimator with another model on the channel, its counter behind and
 * its frames a little older than the followed one's (the fault catalogue's two
 * estimators on one channel: WHENet started a second after the mesh): another
 * publisher, never taken for a late second measurement - its seq and utime
 * are no frame of the followed one. */
static void test_other_model_publisher_not_a_second(void **state)
{
    hkf_head_pose_measurement_t a, b;
    hkf_head_pose_t pose;
    int i, published = 0;
    (void)state;
    for (i = 0; i < 60; ++i) {
        a = measurement(T0 + i * FRAME_US, 1, 0, 10, 0);
        a.seq = 100 + i;
        published += filter_node_receive(&node, &a, a.utime + 2000, &pose);
        if (i >= 30) {
            b = measurement(T0 + i * FRAME_US - 20000, 1, 0, 40, 0); /* captured 20 ms before a */
            b.seq = i - 30;
            b.model = "hopenet";
            assert_int_equal(filter_node_receive(&node, &b, a.utime + 30000, &pose), 0);
        }
    }
    assert_int_equal(published, 60);
    assert_int_equal(node.counts.other_publisher, 30);
    assert_int_equal(node.counts.unpaired, 0);
    assert_int_equal(node.counts.paired, 0);
    assert_true(fabsf(pose.yaw - 10.0f) < 0.5f);
}

/* One frame of a held 30 deg turn: the first reads `first`, the second `second` (its own frame: 6 deg beyond the
 * first's, as the curve has learnt), answered 12 ms after the first; the pose published for the frame's yaw. */
static float held_frame(int frame, double first, double second)
{
    hkf_head_pose_measurement_t m = measurement(T0 + frame * FRAME_US, 1, 1.0, first, 0.0), s = m;
    hkf_head_pose_t pose;
    int published;
    s.model = "hopenet";
    s.yaw = (float)second;
    published = filter_node_receive(&node, &m, m.utime + 8000, &pose);
    published += filter_node_receive(&node, &s, m.utime + 20000, &pose);
    assert_int_equal(published, 1); /* one pose per frame */
    return pose.yaw;
}

/* Frames *frame up to `until` of a hold (held_frame); the last one's pose yaw. */
static float held_until(int *frame, int until, double first, double second)
{
    float yaw = 0.0f;
    for (; *frame < until; ++*frame) {
        yaw = held_frame(*frame, first, second);
    }
    return yaw;
}

/* A gross error is refused before it reaches the filter: a reading 20 deg or more from both the other model's
 * and the track's, while those two agree. A held 30 deg turn; then one frame whose second reading is 40 deg off
 * (the frame takes the second alone at this turn: before, the pose jumped toward it), and a true move of 25 deg in
 * one frame, which both models read and which is followed, not refused. */
static void test_second_model_gross_error_refused(void **state)
{
    int frame = 0;
    float yaw = held_until(&frame, 60, 30.0, 36.0);
    (void)state;
    assert_true(fabsf(yaw - 30.0f) < 1.0f);
    assert_int_equal(node.counts.gross_refused, 0);
    yaw = held_frame(frame++, 30.0, 76.0);
    print_message("a second reading 40 deg off: the pose %.2f\n", yaw);
    assert_true(fabsf(yaw - 30.0f) < 1.0f);
    assert_int_equal(node.counts.gross_refused, 1);
    held_until(&frame, 70, 30.0, 36.0);
    yaw = held_frame(frame++, 55.0, 61.0); /* a move: both models read it */
    print_message("a 25 deg move read by both: the pose %.2f\n", yaw);
    assert_int_equal(node.counts.gross_refused, 1);
    assert_true(yaw > 45.0f);
}

/* Below 25 deg a frame does not wait, but a first reading 20 deg or more from the track's prediction waits for
 * the second's answer: a gross one is refused before its pose goes out (before: the view jumped 37 deg for
 * the frame), and the track stays on the hold. */
static void test_second_model_gross_first_refused_before_its_pose(void **state)
{
    int frame = 0;
    float yaw = held_until(&frame, 60, 15.0, 21.0);
    (void)state;
    assert_true(fabsf(yaw - 15.0f) < 1.0f);
    yaw = held_frame(frame++, -22.0, 21.0);
    print_message("a first reading 37 deg off: its own frame's pose %.2f\n", yaw);
    assert_true(fabsf(yaw - 15.0f) < 1.0f);
    yaw = held_frame(frame++, 15.0, 21.0);
    print_message("the frame after: %.2f\n", yaw);
    assert_int_equal(node.counts.gross_refused, 1);
    assert_true(fabsf(yaw - 15.0f) < 1.0f);
}

/* The first model's measurement waits for the second's where the frame takes the second's alone (|yaw| >=
 * 25 deg), while the second's come promptly: no pose goes out with the first's, one with the second's. A
 * frame after one that waited waits down to 20 deg (no flicker between the two rules at a hold near 25).
 * A second model that stops ends the waiting within the prompt time (FILTER_NODE_PROMPT_SHARE of coast_time),
 * before the track would be LOST. */
static void test_second_model_first_waits_for_it(void **state)
{
    static const struct {
        double yaw;
        int second_sent, first_posed; /* the second's measurement sent; the first's arrival publishes */
    } stretch[] = {{15.0, 1, 1}, {30.0, 1, 0}, {22.0, 1, 0}, {18.0, 1, 1}, {30.0, 1, 0}};
    hkf_head_pose_measurement_t m, second;
    hkf_head_pose_t pose;
    unsigned long awaited;
    int i, k, free_from, frame = 0;
    (void)state;
    for (k = 0; k < 5; ++k) {
        for (i = 0; i < 10; ++i, ++frame) {
            m = measurement(T0 + frame * FRAME_US, 1, 1.0, stretch[k].yaw, 0.0);
            second = m;
            second.model = "hopenet";
            second.yaw = (float)(stretch[k].yaw + 6.0);
            assert_int_equal(filter_node_receive(&node, &m, m.utime + 8000, &pose), stretch[k].first_posed);
            assert_int_equal(filter_node_receive(&node, &second, m.utime + 20000, &pose), !stretch[k].first_posed);
        }
    }
    assert_int_equal(node.counts.awaited, 30);
    /* the second stops: the first waits while a frame of the last prompt time had the second's (200 ms, six
     * frames at 33 ms), then is taken again, and the track is tracking. Each waiting frame's pose goes out
     * without its answer when the next frame comes (one pose per frame, in order): the frame before's, then,
     * once no frame waits, the frame's own too (queued) */
    awaited = node.counts.awaited;
    free_from = (int)(FILTER_NODE_PROMPT_SHARE * 1e6 * (double)config.settings.coast_time / FRAME_US);
    assert_int_equal(free_from, 6);
    for (i = 0; i < free_from + 3; ++i, ++frame) {
        int64_t due;
        m = measurement(T0 + frame * FRAME_US, 1, 1.0, 30.0, 0.0);
        assert_int_equal(filter_node_receive(&node, &m, m.utime + 8000, &pose), i >= 1);
        if (i >= 1) {
            assert_true(pose.utime == m.utime - FRAME_US || i > free_from); /* the frame before's */
            assert_int_equal(pose.status, HKF_HEAD_POSE_T_TRACKING);
        }
        if (i == free_from) { /* the last that waited published; this frame's own queued behind it */
            assert_int_equal(filter_node_await_next(&node, m.utime + 8000, &pose, &due), 1);
            assert_true(pose.utime == m.utime);
        }
        if (i > free_from) {
            assert_true(pose.utime == m.utime);
        }
    }
    assert_int_equal(node.counts.awaited, awaited + (unsigned long)free_from);
    assert_int_equal(node.counts.awaits_expired, (unsigned long)free_from);
}

/* A second model a frame late (its measurement of a frame arrives after the next frame's first, 45 ms after its
 * own first's): the node learns that lateness from the answers (FILTER_NODE_LATENESS_QUANTILE) and waits that long,
 * so the first's still waits at a large turn, and each second measurement publishes its own frame's posterior at
 * that frame's time, not one predicted on to the newest frame (which at the end of a fast turn would overshoot the
 * stop and step back): one pose per frame, in order. */
static void test_second_model_late_publishes_its_frame(void **state)
{
    hkf_head_pose_measurement_t m[40], second;
    hkf_head_pose_t pose;
    int i, published = 0;
    (void)state;
    for (i = 0; i < 40; ++i) {
        m[i] = measurement(T0 + i * FRAME_US, 1, 1.0, i < 10 ? 15.0 : 30.0, 0.0);
        assert_int_equal(filter_node_receive(&node, &m[i], m[i].utime + 8000, &pose), i < 10);
        if (i > 0) {
            second = m[i - 1];
            second.model = "hopenet";
            second.yaw += 6.0f;
            if (filter_node_receive(&node, &second, m[i].utime + 20000, &pose)) {
                ++published;
                assert_true(pose.utime == m[i - 1].utime && pose.measurement_utime == m[i - 1].utime);
                assert_int_equal(pose.status, HKF_HEAD_POSE_T_TRACKING);
            }
        }
    }
    assert_int_equal(published, 29); /* frames 10-38, by their seconds */
    assert_int_equal(node.counts.awaited, 30);
    assert_int_equal(node.counts.awaits_expired, 0);
    print_message("the answers' lateness learnt: %.1f ms (45 ms each)\n", node.second.lateness_us / 1000.0);
    assert_true(node.second.lateness_us > 40000.0 && node.second.lateness_us < 50000.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_second_model_after_recenter, setup),
        cmocka_unit_test_setup(test_second_model_fused_into_its_frame, setup),
        cmocka_unit_test_setup(test_second_model_late_or_repeated_not_used, setup),
        cmocka_unit_test_setup(test_second_model_alone_starts_and_keeps_track, setup),
        cmocka_unit_test_setup(test_second_model_offset_aligned, setup),
        cmocka_unit_test_setup(test_second_model_offset_from_the_first_frames, setup),
        cmocka_unit_test_setup(test_second_model_offset_across_the_seam, setup),
        cmocka_unit_test_setup(test_second_model_alone_at_large_yaw, setup),
        cmocka_unit_test_setup(test_other_model_publisher_not_a_second, setup),
        cmocka_unit_test_setup(test_second_model_first_waits_for_it, setup),
        cmocka_unit_test_setup(test_second_model_gross_error_refused, setup),
        cmocka_unit_test_setup(test_second_model_gross_first_refused_before_its_pose, setup),
        cmocka_unit_test_setup(test_second_model_late_publishes_its_frame, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
