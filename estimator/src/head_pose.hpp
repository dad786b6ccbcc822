// head_pose.hpp - a head pose as every estimator gives it and everything downstream takes it (the
// rotation maths, the drawing, the fusion): the angles, and the position when the model measured it.
#pragma once

#include "head_position.hpp"

namespace hkf_estimator {

struct HeadPose {
    HeadPose() = default;
    HeadPose(float pitch_deg, float yaw_deg, float roll_deg) : pitch(pitch_deg), yaw(yaw_deg), roll(roll_deg) {}
    float pitch = 0.f, yaw = 0.f, roll = 0.f;  // deg, hkf convention (docs/programs.md: "Angle convention")
    bool has_position = false;                 // the model measured the position:
    HeadPosition position;                     // cm, camera frame (head_position.hpp)
};

}  // namespace hkf_estimator
