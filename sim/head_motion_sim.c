/* head_motion_sim.c - see head_motion_sim.h. */
#include "head_motion_sim.h"

#include <math.h>
#include <stddef.h>

#define SIM_PI 3.14159265358979323846

void sim_rng_seed(sim_rng_t *rng, uint64_t seed)
{
    /* splitmix64 once, so that small seeds still give well-mixed states */
    uint64_t z = seed + 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    rng->state = z ? z : 0x2545F4914F6CDD1Dull;
}

double sim_rng_uniform(sim_rng_t *rng)
{
    uint64_t x = rng->state;
    x ^= x >> 12;
    x ^= x << 25;
    x ^= x >> 27;
    rng->state = x;
    return (double)((x * 0x2545F4914F6CDD1Dull) >> 11) * (1.0 / 9007199254740992.0);
}

double sim_rng_gaussian(sim_rng_t *rng)
{
    /* Box-Muller; 1 - u keeps the logarithm's argument in (0, 1] */
    const double u1 = 1.0 - sim_rng_uniform(rng);
    const double u2 = sim_rng_uniform(rng);
    return sqrt(-2.0 * log(u1)) * cos(2.0 * SIM_PI * u2);
}

/* The drive: each step moves (minimum-jerk) to a pose, then holds it. */
typedef struct {
    double move_s, hold_s;
    double pose[3]; /* pitch, yaw, roll */
} script_step_t;

static const script_step_t script[] = {
    {0.0, 3.0, {0.0, 0.0, 0.0}},       /* looking ahead */
    {0.45, 0.8, {-8.0, -55.0, 0.0}},   /* left mirror */
    {0.45, 2.5, {0.5, -0.8, 0.3}},
    {0.35, 0.6, {12.0, 22.0, 2.0}},    /* rear-view mirror */
    {0.35, 2.0, {-0.4, 0.6, -0.2}},
    {0.5, 0.9, {-10.0, 60.0, -3.0}},   /* right mirror */
    {0.5, 2.0, {0.0, 0.0, 0.0}},
    {0.6, 0.5, {-5.0, -100.0, 5.0}},   /* shoulder check */
    {0.6, 2.5, {0.3, 0.4, 0.0}},
    {0.6, 1.5, {-25.0, 5.0, 0.0}},     /* glance at the instruments */
    {0.6, 2.0, {0.0, 0.0, 0.0}},
    {0.8, 1.5, {0.0, 0.0, 18.0}},      /* head tilt */
    {0.8, 2.0, {0.0, -0.5, 0.0}},
    {2.0, 1.0, {10.0, -40.0, -10.0}},  /* a slow look around */
    {2.0, 2.0, {0.0, 0.0, 0.0}},
};
#define SCRIPT_STEPS (sizeof script / sizeof script[0])

double sim_script_period(void)
{
    double total = 0.0;
    size_t i;
    for (i = 0; i < SCRIPT_STEPS; ++i) {
        total += script[i].move_s + script[i].hold_s;
    }
    return total;
}

void sim_head_pose(double t, double pose[3])
{
    const double period = sim_script_period();
    double local = fmod(t, period);
    size_t i;
    int a;
    if (local < 0.0) {
        local += period;
    }
    for (i = 0; i < SCRIPT_STEPS; ++i) {
        const script_step_t *step = &script[i];
        const double *from = script[(i + SCRIPT_STEPS - 1) % SCRIPT_STEPS].pose;
        if (local < step->move_s) {
            const double s = local / step->move_s;
            const double w = s * s * s * (10.0 - 15.0 * s + 6.0 * s * s); /* minimum jerk */
            for (a = 0; a < 3; ++a) {
                pose[a] = from[a] + w * (step->pose[a] - from[a]);
            }
            return;
        }
        local -= step->move_s;
        if (local < step->hold_s) {
            for (a = 0; a < 3; ++a) {
                pose[a] = step->pose[a];
            }
            return;
        }
        local -= step->hold_s;
    }
    for (a = 0; a < 3; ++a) {
        pose[a] = script[SCRIPT_STEPS - 1].pose[a];
    }
}

int sim_head_still(double t)
{
    double before[3], after[3], speed2 = 0.0;
    int a;
    sim_head_pose(t - 0.005, before);
    sim_head_pose(t + 0.005, after);
    for (a = 0; a < 3; ++a) {
        const double v = (after[a] - before[a]) / 0.01;
        speed2 += v * v;
    }
    return speed2 < 1.0;
}

/* The estimator's mean absolute error at a true angle: the FSA-Net curves of
 * the paper's Table I (amplitude form), roll's centre error set to pitch's. */
static double estimator_mae(int axis, double x)
{
    static const double curve[3][4] = {
        /* tau, lambda, mu, sigma */
        {315.43, 312.07, -5.19, 132.41},
        {7.64, 4.11, -0.35, 30.87},
        {329000.0, 328996.64, -0.562, 4440.0},
    };
    const double u = x - curve[axis][2];
    return curve[axis][0] - curve[axis][1] * exp(-u * u / (2.0 * curve[axis][3] * curve[axis][3]));
}

sim_config_t sim_default_config(void)
{
    sim_config_t c;
    c.fps = 30.0;
    c.error_model = SIM_ERRORS_MEASURED;
    c.noise_scale = 1.0;
    /* none: through mesh_pnp, the real clips' raw poses have no outliers (docs/evaluation.md) */
    c.outlier_rate = 0.0;
    c.dropout_rate = 0.004;
    c.dropout_max_s = 0.4;
    c.frame_jitter_s = 0.002;
    return c;
}

sim_config_t sim_assumed_config(void)
{
    sim_config_t c = sim_default_config();
    c.error_model = SIM_ERRORS_ASSUMED;
    c.outlier_rate = 0.005;
    return c;
}

void sim_init(sim_t *sim, const sim_config_t *config, uint64_t seed)
{
    int a;
    sim->config = *config;
    sim_rng_seed(&sim->rng, seed);
    sim->frame = 0;
    for (a = 0; a < 3; ++a) {
        sim->bias[a] = sim_rng_gaussian(&sim->rng);
    }
    for (a = 0; a < 3; ++a) {
        int k, d;
        for (k = 0; k < SIM_BIAS_WAVES; ++k) {
            double norm = 0.0;
            for (d = 0; d < 3; ++d) {
                sim->wave_direction[a][k][d] = sim_rng_gaussian(&sim->rng);
                norm += sim->wave_direction[a][k][d] * sim->wave_direction[a][k][d];
            }
            for (d = 0; d < 3; ++d) {
                sim->wave_direction[a][k][d] /= sqrt(norm > 0.0 ? norm : 1.0);
            }
            /* wavelengths of 30-90 deg: the error changes over a few tens of degrees of turn */
            sim->wave_number[a][k] = 2.0 * SIM_PI / (30.0 + 60.0 * sim_rng_uniform(&sim->rng));
            sim->wave_phase[a][k] = 2.0 * SIM_PI * sim_rng_uniform(&sim->rng);
        }
    }
    sim->dropout_frames_left = 0;
}

/* The measured model's bias at a pose, in units of its standard deviation: a
 * smooth random field over (pitch, yaw, roll), the same whenever the head
 * comes back to a pose (a sum of plane waves; mean square 1 over the phases). */
static double bias_field(const sim_t *sim, int axis, const double pose[3])
{
    double sum = 0.0;
    int k;
    for (k = 0; k < SIM_BIAS_WAVES; ++k) {
        const double *u = sim->wave_direction[axis][k];
        const double along = u[0] * pose[0] + u[1] * pose[1] + u[2] * pose[2];
        sum += cos(sim->wave_number[axis][k] * along + sim->wave_phase[axis][k]);
    }
    return sum * sqrt(2.0 / SIM_BIAS_WAVES);
}

/* The measured model's white frame noise at the curve's centre, deg: what the
 * still frames of the real clips show through mesh_pnp (docs/evaluation.md, the
 * leave-one-out table); against ~3 deg of AFLW2000 error, under 1 % of the error
 * variance. It grows with the pose as the error curve does. */
#define SIM_FRAME_NOISE_DEG 0.25

static double measured_error(sim_t *sim, int axis, const double truth[3], double std)
{
    const double white = SIM_FRAME_NOISE_DEG * sim->config.noise_scale * estimator_mae(axis, truth[axis]) /
                         estimator_mae(axis, 0.0);
    const double rest = std * std - white * white;
    return white * sim_rng_gaussian(&sim->rng) + sqrt(rest > 0.0 ? rest : 0.0) * bias_field(sim, axis, truth);
}

void sim_next(sim_t *sim, sim_frame_t *out)
{
    /* The assumed model: 30 % of the error variance white, 70 % a
     * bias drifting with a 1 s time constant. The measured model: see
     * measured_error. A Gaussian's std is its MAE times sqrt(pi / 2). */
    const double mae_to_std = sqrt(SIM_PI / 2.0);
    const double white = sqrt(0.3), drift = sqrt(0.7);
    const sim_config_t *c = &sim->config;
    const double dt = 1.0 / c->fps;
    const double keep = exp(-dt / 1.0);
    const double nominal = (double)sim->frame * dt;
    double jitter = c->frame_jitter_s * sim_rng_gaussian(&sim->rng);
    int a;

    if (jitter > 0.4 * dt) {
        jitter = 0.4 * dt;
    } else if (jitter < -0.4 * dt) {
        jitter = -0.4 * dt;
    }
    out->time = nominal + (sim->frame > 0 ? jitter : 0.0);
    sim_head_pose(out->time, out->truth);
    out->still = sim_head_still(out->time);

    for (a = 0; a < 3; ++a) {
        const double std = c->noise_scale * mae_to_std * estimator_mae(a, out->truth[a]);
        if (c->error_model == SIM_ERRORS_ASSUMED) {
            sim->bias[a] = keep * sim->bias[a] + sqrt(1.0 - keep * keep) * sim_rng_gaussian(&sim->rng);
            out->measured[a] = out->truth[a] + std * (white * sim_rng_gaussian(&sim->rng) + drift * sim->bias[a]);
        } else {
            out->measured[a] = out->truth[a] + measured_error(sim, a, out->truth, std);
        }
    }
    if (sim_rng_uniform(&sim->rng) < c->outlier_rate) {
        for (a = 0; a < 3; ++a) {
            out->measured[a] += 20.0 * sim_rng_gaussian(&sim->rng);
        }
    }
    if (out->measured[1] >= 180.0) {
        out->measured[1] -= 360.0;
    } else if (out->measured[1] < -180.0) {
        out->measured[1] += 360.0;
    }

    if (sim->dropout_frames_left == 0 && sim_rng_uniform(&sim->rng) < c->dropout_rate) {
        sim->dropout_frames_left = 1 + (int)(sim_rng_uniform(&sim->rng) * c->dropout_max_s * c->fps);
    }
    out->valid = sim->dropout_frames_left == 0;
    if (sim->dropout_frames_left > 0) {
        --sim->dropout_frames_left;
    }
    ++sim->frame;
}
