/*
 * test_reference_eigen_position.cpp - libhkf's position filter (hkf/hkf_position.h) against the textbook.
 *
 * The reference is the position's step written the generic way, in double, sharing no code with libhkf:
 * per axis the motion adaptation's two 2-state filters in matrix form (Eigen), HOLD (F = [[1, 0], [0, 0]],
 * Q = diag(0, p0_rate), R + still_wander) and MOVE (F = [[1, dt], [0, 1]], the white-acceleration Q),
 * each predicted from the common estimate and updated with the full Gaussian likelihood of its
 * innovation, the probability of MOVE by Bayes from the two-state chain's prior, the posteriors merged by
 * the mixture's mean and covariance (GPB1); R = the measurement's scale x the noise level (n handed over,
 * or r_const), within [r_min, r_max]; and the outlier gate as hkf_position.h states it (refused when on
 * an axis z lies beyond max_speed dt + 3 sigmas of both models' innovations). Each step starts from
 * libhkf's own state (hkf_position_get_state), so a step is checked against the equations, not a drift
 * over thousands of them, on long random sequences: rests and leans at up to 60 cm/s, noise of 0.05-0.5 cm,
 * outliers of 5-60 cm, random dt, R scales of 1 and 25, noise levels handed over now and then. Built for
 * float, double and Q16.16.
 */
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include <Eigen/Dense>

#include "hkf/hkf_position.h"
#include "head_motion_sim.h"
#include "reference_reals.hpp"

namespace {

using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;

/* The reference's posterior for one axis, or gated. */
struct AxisResult {
    double x, v, p00, p01, p11, moving;
};

/* One step of the textbook filter from libhkf's state st: z (cm), R r per axis, dt; false when the gate
 * refuses z (the reference's rule), else the posteriors in out. */
bool reference_step(const hkf_position_settings_t &s, const hkf_position_state_t &st, const double z[3],
                    const double r[3], double dt, AxisResult out[3])
{
    const double a_rate = D(s.start_rate), b_rate = D(s.stop_rate), start_var = D(s.p0_rate);
    const double long_run = a_rate / (a_rate + b_rate), fade = std::exp(-(a_rate + b_rate) * dt);
    const double stay_moving = long_run + (1.0 - long_run) * fade, start_moving = long_run * (1.0 - fade);
    const double reach = D(s.max_speed) * dt;
    const Eigen::RowVector2d H(1.0, 0.0);
    Mat2 F[2], Q[2];
    F[0] << 1.0, 0.0, 0.0, 0.0; /* HOLD */
    F[1] << 1.0, dt, 0.0, 1.0;  /* MOVE */
    bool gated = false;
    for (int a = 0; a < 3; ++a) {
        const double q = D(s.process_noise[a]), wander = D(s.still_wander[a]);
        Q[0] << 0.0, 0.0, 0.0, start_var;
        Q[1] << q * dt * dt * dt / 3.0, q * dt * dt / 2.0, q * dt * dt / 2.0, q * dt;
        const Vec2 x(D(st.position[a]), D(st.rate[a]));
        Mat2 P;
        P << D(st.p00[a]), D(st.p01[a]), D(st.p01[a]), D(st.p11[a]);
        Vec2 xj[2];
        Mat2 Pj[2];
        double logL[2], beyond[2];
        for (int j = 0; j < 2; ++j) {
            const Vec2 xp = F[j] * x;
            const Mat2 Pp = F[j] * P * F[j].transpose() + Q[j];
            const double y = z[a] - H * xp;
            const double S = H * Pp * H.transpose() + r[a] + (j == 0 ? wander : 0.0);
            const Vec2 K = Pp * H.transpose() / S;
            xj[j] = xp + K * y;
            Pj[j] = (Mat2::Identity() - K * H) * Pp;
            logL[j] = -0.5 * y * y / S - 0.5 * std::log(2.0 * M_PI * S);
            beyond[j] = std::fabs(y) - reach - 3.0 * std::sqrt(S); /* > 0: beyond this model's reach */
        }
        gated = gated || (D(s.max_speed) > 0 && beyond[0] > 0 && beyond[1] > 0);
        const double prior = D(st.moving[a]) * stay_moving + (1.0 - D(st.moving[a])) * start_moving;
        const double mu = 1.0 / (1.0 + std::exp(std::log1p(-prior) + logL[0] - std::log(prior) - logL[1]));
        const Vec2 xm = (1.0 - mu) * xj[0] + mu * xj[1];
        Mat2 Pm = Mat2::Zero();
        for (int j = 0; j < 2; ++j) {
            const Vec2 d = xj[j] - xm;
            Pm += (j == 0 ? 1.0 - mu : mu) * (Pj[j] + d * d.transpose());
        }
        out[a] = {xm(0), xm(1), Pm(0, 0), Pm(0, 1), Pm(1, 1), mu};
    }
    return !gated;
}

/* The worst differences over a run, and what the run exercised. */
struct Worst {
    double position = 0, rate = 0, variance = 0, moving = 0;
    long compared = 0, gated = 0, moves = 0, rests = 0;
};

/* A head's true position: rests and leans (a speed held for a while), about 60 cm from the camera. */
void move_head(sim_rng_t &rng, double dt, double truth[3], double speed[3])
{
    if (sim_rng_uniform(&rng) < dt * 1.5) { /* a new lean or a rest, 1.5 a second */
        const bool rest = sim_rng_uniform(&rng) < 0.5;
        for (int a = 0; a < 3; ++a) {
            speed[a] = rest ? 0.0 : (sim_rng_uniform(&rng) - 0.5) * (a == 2 ? 120.0 : 60.0);
        }
    }
    for (int a = 0; a < 3; ++a) {
        truth[a] += speed[a] * dt;
    }
    truth[2] = std::min(std::max(truth[2], 30.0), 120.0); /* within a cockpit */
    truth[0] = std::min(std::max(truth[0], -40.0), 40.0);
    truth[1] = std::min(std::max(truth[1], -30.0), 30.0);
}

/* The measurement of a step: the truth with noise of sd (cm), now and then an outlier. */
void measure(sim_rng_t &rng, const double truth[3], double sd, hkf_real_t z[3], double zd[3])
{
    const bool outlier = sim_rng_uniform(&rng) < 0.01;
    for (int a = 0; a < 3; ++a) {
        zd[a] = truth[a] + (sim_rng_uniform(&rng) - 0.5) * sd * std::sqrt(12.0);
        if (outlier) {
            zd[a] += (sim_rng_uniform(&rng) < 0.5 ? -1.0 : 1.0) * (5.0 + 55.0 * sim_rng_uniform(&rng));
        }
        z[a] = R(zd[a]);
        zd[a] = D(z[a]); /* what the filter sees */
    }
}

/* R per axis as hkf_position.h states it. */
void r_of(const hkf_position_settings_t &s, const hkf_position_state_t &st, double scale, double r[3])
{
    for (int a = 0; a < 3; ++a) {
        r[a] = std::min(std::max(D(R(D(st.noise[a]) * scale)), D(s.r_min)), D(s.r_max));
    }
}

void record(const AxisResult ref[3], const hkf_position_state_t &after, Worst &w)
{
    for (int a = 0; a < 3; ++a) {
        w.position = std::max(w.position, std::fabs(D(after.position[a]) - ref[a].x));
        w.rate = std::max(w.rate, std::fabs(D(after.rate[a]) - ref[a].v) / (1.0 + std::fabs(ref[a].v)));
        w.variance = std::max(w.variance, std::fabs(D(after.p00[a]) - ref[a].p00) / (1e-3 + ref[a].p00));
        w.moving = std::max(w.moving, std::fabs(D(after.moving[a]) - ref[a].moving));
        w.moves += ref[a].moving > 0.9;
        w.rests += ref[a].moving < 0.1;
    }
    ++w.compared;
}

/* One run: libhkf and the reference side by side on a seed's sequence; false on a disagreement the
 * build's tolerance does not allow (said). */
bool run(const hkf_position_settings_t &s, const char *name, std::uint64_t seed, long steps, Worst &w)
{
    hkf_position_filter_t f;
    sim_rng_t rng;
    double truth[3] = {0.0, 0.0, 60.0}, speed[3] = {0.0, 0.0, 0.0};
    if (hkf_position_init(&f, &s) != HKF_OK) {
        std::fprintf(stderr, "%s: hkf_position_init refused the settings\n", name);
        return false;
    }
    sim_rng_seed(&rng, seed);
    for (long i = 0; i < steps; ++i) {
        const double dt = D(R(1.0 / 90.0 + sim_rng_uniform(&rng) * (1.0 / 20.0 - 1.0 / 90.0)));
        const double sd = 0.05 + 0.45 * sim_rng_uniform(&rng), scale = sim_rng_uniform(&rng) < 0.2 ? 25.0 : 1.0;
        hkf_real_t z[3];
        double zd[3], r[3];
        hkf_position_state_t before, after;
        hkf_position_output_t out;
        AxisResult ref[3];
        move_head(rng, dt, truth, speed);
        measure(rng, truth, sd, z, zd);
        if (sim_rng_uniform(&rng) < 0.01) { /* a noise level handed over, as the calibration does */
            const hkf_real_t n[3] = {R(0.001 + 0.01 * sim_rng_uniform(&rng)), R(0.001 + 0.01 * sim_rng_uniform(&rng)),
                                     R(0.01 + 0.2 * sim_rng_uniform(&rng))};
            (void)hkf_position_set_noise(&f, n);
        }
        const bool started = hkf_position_started(&f);
        (void)hkf_position_get_state(&f, &before);
        r_of(s, before, scale, r);
        const bool taken = started && reference_step(s, before, zd, r, dt, ref);
        if (hkf_position_update(&f, z, R(scale), R(dt), &out) != HKF_OK) {
            std::fprintf(stderr, "%s step %ld: hkf_position_update failed\n", name, i);
            return false;
        }
        if (!started) {
            continue;
        }
        const bool refused = (out.flags & HKF_FLAG_GATED) != 0;
        if (refused == taken && (out.flags & HKF_FLAG_REACQUIRED) == 0) {
            std::fprintf(stderr, "%s step %ld: libhkf %s, the reference %s\n", name, i, refused ? "gated" : "took it",
                         taken ? "took it" : "gated");
            return false;
        }
        if (refused || (out.flags & HKF_FLAG_REACQUIRED) != 0) {
            w.gated += refused;
            continue;
        }
        (void)hkf_position_get_state(&f, &after);
        record(ref, after, w);
    }
    return true;
}

} // namespace

int main(int argc, char **argv)
{
    const long steps = argc > 1 ? std::strtol(argv[1], nullptr, 10) : 20000;
    hkf_position_settings_t wide = hkf_position_default_settings; /* a livelier chain and a tighter gate */
    wide.start_rate = R(5.0);
    wide.stop_rate = R(5.0);
    wide.max_speed = R(100.0);
    const struct {
        const char *name;
        hkf_position_settings_t s;
    } cases[] = {{"defaults", hkf_position_default_settings}, {"lively+tight gate", wide}};
#if defined(HKF_REAL_FIXED)
    const double position_tol = 0.02, rate_tol = 0.05, variance_tol = 0.05, moving_tol = 0.05;
#else
    const double position_tol = 10 * TEST_TOL, rate_tol = 100 * TEST_TOL, variance_tol = 100 * TEST_TOL,
                 moving_tol = 100 * TEST_TOL;
#endif
    int failures = 0;
    if (steps < 1000) {
        std::fprintf(stderr, "usage: %s [STEPS >= 1000]\n", argv[0]);
        return EXIT_FAILURE;
    }
    for (const auto &c : cases) {
        for (std::uint64_t seed = 1; seed <= 3; ++seed) {
            Worst w;
            const bool ran = run(c.s, c.name, seed, steps, w);
            const bool exercised = w.gated > 0 && w.moves > 100 && w.rests > 100;
            const bool ok = ran && exercised && w.position <= position_tol && w.rate <= rate_tol &&
                            w.variance <= variance_tol && w.moving <= moving_tol;
            std::printf("%-4s %-18s seed %llu: %ld steps compared; worst |position| %.1e cm, rate %.1e (rel), "
                        "variance %.1e (rel), MOVE's probability %.1e; %ld gated, %ld axis-steps moving, %ld at rest\n",
                        ok ? "OK" : "FAIL", c.name, static_cast<unsigned long long>(seed), w.compared, w.position,
                        w.rate, w.variance, w.moving, w.gated, w.moves, w.rests);
            failures += !ok;
        }
    }
    return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
