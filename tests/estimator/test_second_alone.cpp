// test_second_alone.cpp - where hkf-estimator leaves a frame to the second model alone
// (first_model_set_aside, estimator/src/frames/second_model.hpp): its newest answer must have a pose, be of a
// frame at most kSetAsideRecentUs before, and read |yaw| >= the option, on either side; 0 turns it off.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <optional>

#include "second_model.hpp"

extern "C" {  // last: cmocka's fail() macro would break the C++ headers
#include <cmocka.h>
}

using hkf_estimator::first_model_set_aside;
using hkf_estimator::kSetAsideRecentUs;
using hkf_estimator::SecondAnswer;

namespace {

constexpr int64_t kFrame = 1700000000000000LL;  // the new frame's capture time, us
constexpr int64_t kFramePeriod = 33333;

std::optional<SecondAnswer> answer(int64_t before_us, float yaw) { return SecondAnswer{kFrame - before_us, yaw}; }

void test_a_recent_big_turn_sets_the_first_aside(void **)
{
    assert_true(first_model_set_aside(answer(kFramePeriod, 65.f), kFrame, 60.f));
    assert_true(first_model_set_aside(answer(kFramePeriod, -65.f), kFrame, 60.f));  // the other side
    assert_true(first_model_set_aside(answer(kFramePeriod, 60.f), kFrame, 60.f));   // from the option on
    assert_true(first_model_set_aside(answer(kSetAsideRecentUs, 65.f), kFrame, 60.f));
}

void test_otherwise_the_first_model_runs(void **)
{
    assert_false(first_model_set_aside(std::nullopt, kFrame, 60.f));                         // no answer with a pose
    assert_false(first_model_set_aside(answer(kFramePeriod, 59.f), kFrame, 60.f));          // a smaller turn
    assert_false(first_model_set_aside(answer(kFramePeriod, -59.f), kFrame, 60.f));
    assert_false(first_model_set_aside(answer(kSetAsideRecentUs + 1, 65.f), kFrame, 60.f));  // too old
    assert_false(first_model_set_aside(answer(kFramePeriod, 90.f), kFrame, 0.f));           // 0: never
}

}  // namespace

int main()
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_a_recent_big_turn_sets_the_first_aside),
        cmocka_unit_test(test_otherwise_the_first_model_runs),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
