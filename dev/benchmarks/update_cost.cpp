/*
 * hkf-bench-update - one filter step of the paper's filter done four ways,
 * for counting instructions under callgrind (dev/benchmarks/update_cost.py):
 *
 *   step_libhkf_paper     hkf_update, adaptive R (Eq. 8) + loop closure (Eq. 9)
 *   step_libhkf_constant  hkf_update, constant R, no loop closure
 *   step_libhkf_defaults  hkf_update with hkf_default_settings (the motion adaptation; R at the noise
 *                         level the calibration beside it measured)
 *   step_libhkf_calibration  hkf_calibration_update after it: the noise calibration's step
 *   step_libhkf_rest      hkf_rest_update: the player's rest, while one is measured (asked again when done)
 *   step_libhkf_position  hkf_position_update: the head's position (x, y, z), default settings
 *   step_libhkf_position_calibration  hkf_calibration_update_position after it: the position's calibration
 *   step_libhkf_pair      hkf_update_pair: the paper's filter, a second estimator's measurement
 *                         with Hopenet's curves (two measurements, not the same work)
 *   step_libhkf_pair_prepared  hkf_update_pair_prepared: the same, the second model prepared once
 *                         (hkf_model_noise_init); the same posteriors, checked
 *   step_opencv           cv::KalmanFilter(6, 3): predict + correct
 *   step_eigen            a fixed-size Eigen 6-state filter, generic matrix form
 *
 * Every variant does the same work per step: set F and Q for this dt,
 * predict, loop closure, R from Eq. 8, yaw wrap, update. All run on the same
 * simulated drive; the program prints how far the others' posteriors are from
 * libhkf's, so the counts compare like with like.
 */
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <Eigen/Dense>
#include <opencv2/video/tracking.hpp>

#include "hkf/hkf.h"
#include "hkf/hkf_calibration.h"
#include "hkf/hkf_rest.h"
#include "hkf/hkf_position.h"
#include "head_motion_sim.h"

#define NOINLINE __attribute__((noipa)) /* no inlining, no merging of the two libhkf steps */

namespace {

struct Input {
    float z[3];
    float dt;
};

float wrap180(float x)
{
    float w = std::fmod(x + 180.0f, 360.0f);
    return (w < 0.0f ? w + 360.0f : w) - 180.0f;
}

/* The paper's measurement side, shared by the OpenCV and Eigen variants. */
struct PaperMeasurementModel {
    const hkf_settings_t &s;
    float centre[3];
    bool centred = false;

    void closeLoop(const float z[3], float zc[3]) const /* Eq. 9 */
    {
        float d[3], n2 = 0.0f;
        for (int a = 0; a < 3; ++a) {
            d[a] = a == 1 ? wrap180(z[a] - centre[a]) : z[a] - centre[a];
            n2 += d[a] * d[a];
            zc[a] = z[a];
        }
        if (n2 <= s.lc_theta * s.lc_theta) {
            for (int a = 0; a < 3; ++a) {
                zc[a] = centre[a] + s.lc_xi * d[a];
            }
            zc[1] = wrap180(zc[1]);
        }
    }

    float noise(int a, float x) const /* Eq. 8 */
    {
        const hkf_noise_curve_t &c = s.noise[a];
        const float u = x - c.mu;
        const float e = c.tau - c.lambda * std::exp(-u * u / (2.0f * c.sigma * c.sigma));
        return std::min(std::max(e, s.r_min), s.r_max);
    }
};

struct OpenCvFilter {
    cv::KalmanFilter kf{6, 3, 0, CV_32F};
    PaperMeasurementModel model;
    bool started = false;

    explicit OpenCvFilter(const hkf_settings_t &s) : model{s, {0, 0, 0}}
    {
        kf.measurementMatrix = cv::Mat::zeros(3, 6, CV_32F);
        for (int a = 0; a < 3; ++a) {
            kf.measurementMatrix.at<float>(a, a) = 1.0f;
        }
    }
};

struct EigenFilter {
    using Vec6 = Eigen::Matrix<float, 6, 1>;
    using Mat6 = Eigen::Matrix<float, 6, 6>;
    Vec6 x = Vec6::Zero();
    Mat6 P = Mat6::Zero();
    PaperMeasurementModel model;
    bool started = false;

    explicit EigenFilter(const hkf_settings_t &s) : model{s, {0, 0, 0}} {}
};

} // namespace

extern "C" {

NOINLINE int step_libhkf_paper(hkf_filter_t *f, const Input *in, hkf_output_t *out)
{
    return hkf_update(f, in->z, in->dt, out);
}

NOINLINE int step_libhkf_constant(hkf_filter_t *f, const Input *in, hkf_output_t *out)
{
    return hkf_update(f, in->z, in->dt, out);
}

NOINLINE int step_libhkf_defaults(hkf_filter_t *f, const Input *in, hkf_output_t *out)
{
    return hkf_update(f, in->z, in->dt, out);
}

NOINLINE int step_libhkf_calibration(hkf_calibration_t *c, hkf_filter_t *f, const Input *in)
{
    return hkf_calibration_update(c, f, in->z, in->dt);
}

NOINLINE int step_libhkf_rest(hkf_rest_t *r, const Input *in)
{
    return hkf_rest_update(r, in->z, in->dt);
}

NOINLINE int step_libhkf_pair(hkf_filter_t *f, const Input *in, const hkf_model_noise_t *second, hkf_output_t *out)
{
    const hkf_real_t z2[3] = {in->z[0] + 1.5f, in->z[1] - 2.0f, in->z[2] + 0.5f};
    return hkf_update_pair(f, in->z, z2, second, in->dt, out);
}

NOINLINE int step_libhkf_pair_prepared(hkf_filter_t *f, const Input *in, const hkf_model_prepared_t *second,
                                      hkf_output_t *out)
{
    const hkf_real_t z2[3] = {in->z[0] + 1.5f, in->z[1] - 2.0f, in->z[2] + 0.5f};
    return hkf_update_pair_prepared(f, in->z, z2, second, in->dt, out);
}

NOINLINE int step_libhkf_position(hkf_position_filter_t *f, const Input *in, hkf_position_output_t *out)
{
    /* a head about 60 cm away moving with the drive's angles (any signal will do: the step has no branches on it) */
    const hkf_real_t xyz[3] = {0.2f * in->z[1], 0.1f * in->z[0], 60.0f + 0.1f * in->z[2]};
    return hkf_position_update(f, xyz, 1.0f, in->dt, out);
}

NOINLINE int step_libhkf_position_calibration(hkf_calibration_t *c, hkf_position_filter_t *f, const Input *in)
{
    const hkf_real_t xyz[3] = {0.2f * in->z[1], 0.1f * in->z[0], 60.0f + 0.1f * in->z[2]}; /* the step's own */
    return hkf_calibration_update_position(c, f, xyz, in->dt);
}

NOINLINE void step_opencv(OpenCvFilter *k, const Input *in, float yaw_out[1])
{
    const hkf_settings_t &s = k->model.s;
    if (!k->started) {
        k->kf.statePost = cv::Mat::zeros(6, 1, CV_32F);
        k->kf.errorCovPost = cv::Mat::zeros(6, 6, CV_32F);
        for (int a = 0; a < 3; ++a) {
            k->kf.statePost.at<float>(a) = in->z[a];
            k->kf.errorCovPost.at<float>(a, a) = s.p0_angle;
            k->kf.errorCovPost.at<float>(a + 3, a + 3) = s.p0_rate;
            k->model.centre[a] = in->z[a];
        }
        k->started = true;
        yaw_out[0] = in->z[1];
        return;
    }
    const float dt = in->dt;
    cv::Mat &F = k->kf.transitionMatrix;
    cv::Mat &Q = k->kf.processNoiseCov;
    cv::setIdentity(F);
    Q.setTo(0);
    for (int a = 0; a < 3; ++a) {
        const float q = s.process_noise[a];
        F.at<float>(a, a + 3) = dt;
        Q.at<float>(a, a) = q * dt * dt * dt / 3.0f;
        Q.at<float>(a, a + 3) = Q.at<float>(a + 3, a) = q * dt * dt / 2.0f;
        Q.at<float>(a + 3, a + 3) = q * dt;
    }
    const cv::Mat &prior = k->kf.predict();
    float zc[3];
    k->model.closeLoop(in->z, zc);
    cv::Mat &R = k->kf.measurementNoiseCov;
    R.setTo(0);
    for (int a = 0; a < 3; ++a) {
        R.at<float>(a, a) = k->model.noise(a, zc[a]);
    }
    /* OpenCV forms y = z - H x itself: unwrap the yaw measurement around the prior */
    const float prior_yaw = prior.at<float>(1);
    cv::Mat z = (cv::Mat_<float>(3, 1) << zc[0], prior_yaw + wrap180(zc[1] - prior_yaw), zc[2]);
    cv::Mat &post = const_cast<cv::Mat &>(k->kf.correct(z));
    post.at<float>(1) = wrap180(post.at<float>(1));
    yaw_out[0] = post.at<float>(1);
}

NOINLINE void step_eigen(EigenFilter *k, const Input *in, float yaw_out[1])
{
    using Mat6 = EigenFilter::Mat6;
    using Mat36 = Eigen::Matrix<float, 3, 6>;
    const hkf_settings_t &s = k->model.s;
    if (!k->started) {
        k->x.setZero();
        k->P.setZero();
        for (int a = 0; a < 3; ++a) {
            k->x(a) = in->z[a];
            k->P(a, a) = s.p0_angle;
            k->P(a + 3, a + 3) = s.p0_rate;
            k->model.centre[a] = in->z[a];
        }
        k->started = true;
        yaw_out[0] = in->z[1];
        return;
    }
    const float dt = in->dt;
    Mat6 F = Mat6::Identity();
    Mat6 Q = Mat6::Zero();
    for (int a = 0; a < 3; ++a) {
        const float q = s.process_noise[a];
        F(a, a + 3) = dt;
        Q(a, a) = q * dt * dt * dt / 3.0f;
        Q(a, a + 3) = Q(a + 3, a) = q * dt * dt / 2.0f;
        Q(a + 3, a + 3) = q * dt;
    }
    k->x = F * k->x;
    k->x(1) = wrap180(k->x(1));
    k->P = F * k->P * F.transpose() + Q;
    float zc[3];
    k->model.closeLoop(in->z, zc);
    Eigen::Matrix3f R = Eigen::Matrix3f::Zero();
    for (int a = 0; a < 3; ++a) {
        R(a, a) = k->model.noise(a, zc[a]);
    }
    Mat36 H = Mat36::Zero();
    H.leftCols<3>().setIdentity();
    Eigen::Vector3f y = Eigen::Vector3f(zc[0], zc[1], zc[2]) - H * k->x;
    y(1) = wrap180(y(1));
    const Eigen::Matrix3f S = H * k->P * H.transpose() + R;
    const Eigen::Matrix<float, 6, 3> K = k->P * H.transpose() * S.inverse();
    k->x += K * y;
    k->x(1) = wrap180(k->x(1));
    k->P = (Mat6::Identity() - K * H) * k->P;
    yaw_out[0] = k->x(1);
}

} // extern "C"

/* --version, --help and STEPS: -1 to run with *steps, else the exit code. */
static int parse_arguments(int argc, char **argv, long *steps)
{
    if (argc > 1 && std::strcmp(argv[1], "--version") == 0) {
        std::printf("hkf-bench-update %s\n", HKF_VERSION);
        return 0;
    }
    if (argc > 1 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
        std::printf("usage: hkf-bench-update [STEPS]\n"
                    "Runs STEPS (default 20000) filter steps of a simulated drive through libhkf,\n"
                    "cv::KalmanFilter and an Eigen 6-state filter. Count instructions with\n"
                    "dev/benchmarks/update_cost.py, which runs this under callgrind.\n");
        return 0;
    }
    *steps = 20000;
    if (argc > 1) {
        char *end = nullptr;
        *steps = std::strtol(argv[1], &end, 10);
        if (*end != '\0' || *steps < 10 || *steps > 10000000) {
            std::fprintf(stderr, "hkf-bench-update: STEPS must be a whole number from 10 to 10000000, not '%s'\n", argv[1]);
            return 2;
        }
    }
    return -1;
}

/* The simulated drive's measurements; every frame has a face, so every step is a full update. */
static std::vector<Input> drive_inputs(long steps)
{
    sim_config_t config = sim_default_config();
    config.dropout_rate = 0.0;
    sim_t sim;
    sim_init(&sim, &config, 1u);
    std::vector<Input> inputs(static_cast<size_t>(steps));
    double previous = 0.0;
    for (Input &in : inputs) {
        sim_frame_t frame;
        sim_next(&sim, &frame);
        for (int a = 0; a < 3; ++a) {
            in.z[a] = static_cast<float>(frame.measured[a]);
        }
        in.dt = static_cast<float>(frame.time - previous);
        previous = frame.time;
    }
    return inputs;
}

/* libhkf's filters, each variant's own, as main steps them. */
struct LibhkfFilters {
    hkf_filter_t paper, constant, defaults, pair, pair_prepared;
    hkf_calibration_t calibration, position_calibration;
    hkf_model_noise_t second;
    hkf_model_prepared_t second_prepared;
    hkf_position_filter_t position;
    hkf_rest_t rest;
};

/* The variants' settings (paper: the paper's, its loop closure widened) and filters; false when one fails (said). */
static bool init_libhkf(LibhkfFilters *l, const hkf_settings_t &paper)
{
    hkf_settings_t constant = paper, hopenet = paper;
    constant.noise_mode = HKF_NOISE_CONSTANT;
    constant.loop_closure = HKF_LOOP_CLOSURE_OFF;
    for (int a = 0; a < 3; ++a) hopenet.noise[a] = hkf_noise_hopenet[a];
    l->second = hkf_model_noise_of(&hopenet);
    if (hkf_init(&l->paper, &paper) != HKF_OK || hkf_init(&l->constant, &constant) != HKF_OK ||
        hkf_init(&l->defaults, &hkf_default_settings) != HKF_OK || hkf_init(&l->pair, &paper) != HKF_OK ||
        hkf_init(&l->pair_prepared, &paper) != HKF_OK || hkf_model_noise_init(&l->second_prepared, &l->second) != HKF_OK ||
        hkf_calibration_init(&l->calibration, &hkf_default_calibration_settings, &l->defaults) != HKF_OK ||
        hkf_position_init(&l->position, &hkf_position_default_settings) != HKF_OK ||
        hkf_calibration_init_position(&l->position_calibration, &hkf_default_calibration_settings, &l->position) !=
            HKF_OK ||
        hkf_rest_init(&l->rest, &hkf_default_rest_settings) != HKF_OK || hkf_rest_start(&l->rest) != HKF_OK) {
        std::fprintf(stderr, "hkf-bench-update: a libhkf init failed\n");
        return false;
    }
    return true;
}

/* One step of every libhkf variant on in; *paper_out the paper's posterior; *pair_differences counts the
 * steps where the prepared pair differs from hkf_update_pair. false when a step fails (said). */
static bool step_libhkf(LibhkfFilters *l, const Input &in, hkf_output_t *paper_out, long *pair_differences)
{
    hkf_output_t b, c, d, e;
    hkf_position_output_t position;
    if (step_libhkf_paper(&l->paper, &in, paper_out) != HKF_OK || step_libhkf_constant(&l->constant, &in, &b) != HKF_OK ||
        step_libhkf_defaults(&l->defaults, &in, &c) != HKF_OK ||
        step_libhkf_calibration(&l->calibration, &l->defaults, &in) != HKF_OK ||
        step_libhkf_pair(&l->pair, &in, &l->second, &d) != HKF_OK ||
        step_libhkf_pair_prepared(&l->pair_prepared, &in, &l->second_prepared, &e) != HKF_OK ||
        step_libhkf_position(&l->position, &in, &position) != HKF_OK ||
        step_libhkf_position_calibration(&l->position_calibration, &l->position, &in) != HKF_OK) {
        std::fprintf(stderr, "hkf-bench-update: a libhkf step failed\n");
        return false;
    }
    const int rest = step_libhkf_rest(&l->rest, &in);
    if (rest < 0 || (rest == HKF_REST_MEASURED && hkf_rest_start(&l->rest) != HKF_OK)) { /* always measuring */
        std::fprintf(stderr, "hkf-bench-update: the rest's step failed\n");
        return false;
    }
    *pair_differences += std::memcmp(d.angle, e.angle, sizeof d.angle) != 0 || std::memcmp(d.r, e.r, sizeof d.r) != 0;
    return true;
}

int main(int argc, char **argv)
{
    long steps = 0;
    const int exit_code = parse_arguments(argc, argv, &steps);
    if (exit_code >= 0) {
        return exit_code;
    }
    const std::vector<Input> inputs = drive_inputs(steps);
    hkf_settings_t paper = hkf_paper_settings;
    paper.lc_theta = 6.0f; /* wider than the paper's 2 deg so this noisy drive closes the loop often */
    static LibhkfFilters libhkf;
    if (!init_libhkf(&libhkf, paper)) {
        return 1;
    }
    OpenCvFilter cv_filter(paper);
    EigenFilter eigen_filter(paper);

    double worst_cv = 0.0, worst_eigen = 0.0;
    long closures = 0, pair_differences = 0;
    for (const Input &in : inputs) {
        hkf_output_t a;
        float yaw_cv, yaw_eigen;
        if (!step_libhkf(&libhkf, in, &a, &pair_differences)) {
            return 1;
        }
        step_opencv(&cv_filter, &in, &yaw_cv);
        step_eigen(&eigen_filter, &in, &yaw_eigen);
        closures += (a.flags & HKF_FLAG_LOOP_CLOSURE) != 0;
        worst_cv = std::max(worst_cv, static_cast<double>(std::fabs(wrap180(yaw_cv - a.angle[1]))));
        worst_eigen = std::max(worst_eigen, static_cast<double>(std::fabs(wrap180(yaw_eigen - a.angle[1]))));
    }
    std::printf("steps %ld\nloop_closures %ld\nworst_yaw_difference_opencv %.2e\nworst_yaw_difference_eigen %.2e\n"
                "pair_prepared_differences %ld\n",
                steps, closures, worst_cv, worst_eigen, pair_differences);
    return 0;
}
