// The angle convention both ways: pose -> rotation -> pose is the identity,
// and each angle moves the head axes the documented way.
#include <cmath>
#include <cstdio>

#include "head_rotation.hpp"

int main()
{
    using namespace hkf_estimator;
    int passed = 0, failed = 0;
    auto check = [&](bool ok, const char *what) {
        std::printf("%s %s\n", ok ? "ok  " : "FAIL", what);
        ok ? ++passed : ++failed;
    };
    double worst = 0.0;
    for (float pitch = -80.f; pitch <= 80.f; pitch += 20.f)
        for (float yaw = -170.f; yaw <= 170.f; yaw += 17.f)
            for (float roll = -80.f; roll <= 80.f; roll += 20.f) {
                const HeadPose back = pose_from_rotation(rotation_from_pose({pitch, yaw, roll}));
                worst = std::max({worst, static_cast<double>(std::fabs(back.pitch - pitch)),
                                  static_cast<double>(std::fabs(back.yaw - yaw)), static_cast<double>(std::fabs(back.roll - roll))});
            }
    std::printf("round trip: worst error %.2e deg\n", worst);
    check(worst < 1e-3, "pose -> rotation -> pose");
    const cv::Vec3d nose(0, 0, -1), up(0, -1, 0), right_ear(-1, 0, 0);
    check((rotation_from_pose({0.f, 30.f, 0.f}) * nose)[0] < -0.4, "yaw > 0: the nose turns to the subject's right (image -x)");
    check((rotation_from_pose({30.f, 0.f, 0.f}) * nose)[1] < -0.4, "pitch > 0: the nose lifts (image -y)");
    check((rotation_from_pose({0.f, 0.f, 30.f}) * right_ear)[1] > 0.4, "roll > 0: the right ear goes down (image +y)");
    check((rotation_from_pose({0.f, 0.f, 30.f}) * up)[0] < -0.4, "roll > 0: the head's top leans to the image's left");
    std::printf("%d passed, %d failed\n", passed, failed);
    return failed == 0 ? 0 : 1;
}
