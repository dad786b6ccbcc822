// The generated C++ types and the generated C types agree on the wire:
// encoded by one, decoded by the other, field for field.
#include <cstdio>
#include <cstring>
#include <vector>

#include "hkf/head_pose_measurement_t.hpp"
#include "hkf/head_pose_t.hpp"
#include "hkf/tracker_command_t.hpp"
#include "hkf_head_pose_measurement_t.h"
#include "hkf_head_pose_t.h"
#include "hkf_tracker_command_t.h"

static int failures = 0, checks = 0;
#define CHECK(condition)                                                 \
    do {                                                                 \
        ++checks;                                                        \
        if (!(condition)) {                                              \
            std::fprintf(stderr, "FAIL %s:%d: %s\n", __FILE__, __LINE__, #condition); \
            ++failures;                                                  \
        }                                                                \
    } while (0)

int main()
{
    // C++ -> C
    hkf::head_pose_measurement_t m;
    m.utime = 1700000000000001LL;
    m.seq = 3;
    m.model = "whenet";
    m.valid = true;
    m.pitch = -1.5f;
    m.yaw = 120.25f;
    m.roll = 7.0f;
    for (int i = 0; i < 4; ++i) m.face_box[i] = 10.0f * static_cast<float>(i);
    m.detection_score = 0.5f;
    m.inference_us = 1234;
    std::vector<unsigned char> buffer(static_cast<size_t>(m.getEncodedSize()));
    CHECK(m.encode(buffer.data(), 0, static_cast<int>(buffer.size())) == static_cast<int>(buffer.size()));
    hkf_head_pose_measurement_t c;
    CHECK(hkf_head_pose_measurement_t_decode(buffer.data(), 0, static_cast<int>(buffer.size()), &c) > 0);
    CHECK(c.utime == m.utime && c.seq == 3 && std::strcmp(c.model, "whenet") == 0 && c.valid == 1);
    CHECK(c.pitch == -1.5f && c.yaw == 120.25f && c.roll == 7.0f && c.face_box[3] == 30.0f);
    CHECK(c.detection_score == 0.5f && c.inference_us == 1234);
    hkf_head_pose_measurement_t_decode_cleanup(&c);

    // C -> C++
    hkf_head_pose_t p;
    std::memset(&p, 0, sizeof p);
    p.utime = 42;
    p.status = HKF_HEAD_POSE_T_LOST;
    p.yaw = -179.5f;
    p.r[1] = 7.5f;
    p.extrapolated = 1;
    std::vector<unsigned char> pose_buffer(static_cast<size_t>(hkf_head_pose_t_encoded_size(&p)));
    CHECK(hkf_head_pose_t_encode(pose_buffer.data(), 0, static_cast<int>(pose_buffer.size()), &p) > 0);
    hkf::head_pose_t q = hkf::head_pose_t();
    CHECK(q.decode(pose_buffer.data(), 0, static_cast<int>(pose_buffer.size())) > 0);
    CHECK(q.utime == 42 && q.status == hkf::head_pose_t::LOST && q.yaw == -179.5f && q.r[1] == 7.5f && q.extrapolated);

    hkf::tracker_command_t command;
    command.utime = 9;
    command.command = hkf::tracker_command_t::RECENTER;
    std::vector<unsigned char> command_buffer(static_cast<size_t>(command.getEncodedSize()));
    CHECK(command.encode(command_buffer.data(), 0, static_cast<int>(command_buffer.size())) > 0);
    hkf_tracker_command_t cc;
    CHECK(hkf_tracker_command_t_decode(command_buffer.data(), 0, static_cast<int>(command_buffer.size()), &cc) > 0);
    CHECK(cc.command == HKF_TRACKER_COMMAND_T_RECENTER && cc.utime == 9);

    std::printf("%d passed, %d failed\n", checks - failures, failures);
    return failures == 0 ? 0 : 1;
}
