/* pose_angles.h: the short way round and a pose from its centre, at the seam and beyond it. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

#include "pose_angles.h"

static void test_wrap(void **state)
{
    (void)state;
    assert_true(pose_angle_wrap(0.0) == 0.0);
    assert_true(pose_angle_wrap(180.0) == -180.0); /* [-180, 180): 180 is -180 */
    assert_true(pose_angle_wrap(-180.0) == -180.0);
    assert_true(pose_angle_wrap(540.0) == -180.0);
    assert_true(pose_angle_wrap(-190.0) == 170.0);
    assert_true(pose_angle_wrap(190.0) == -170.0);
    assert_true(fabs(pose_angle_wrap(359.5) + 0.5) < 1e-12);
    assert_true(fabs(pose_angle_wrap(-719.25) - 0.75) < 1e-12);
}

static void test_from_center(void **state)
{
    hkf_head_pose_t pose;
    double angles[3], position[3];
    (void)state;
    memset(&pose, 0, sizeof pose);
    pose.pitch = 10.0f, pose.yaw = 175.0f, pose.roll = -178.0f;
    pose.center[0] = 2.0f, pose.center[1] = -175.0f, pose.center[2] = 178.0f;
    pose.x = 3.0f, pose.y = -2.0f, pose.z = 55.0f;
    pose.position_center[0] = 1.0f, pose.position_center[1] = 1.0f, pose.position_center[2] = 60.0f;
    pose_from_center(&pose, angles, position);
    assert_true(angles[0] == 8.0 && angles[1] == -10.0 && angles[2] == 4.0); /* across the seam: the short way */
    assert_true(position[0] == 2.0 && position[1] == -3.0 && position[2] == -5.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_wrap),
        cmocka_unit_test(test_from_center),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
