/*
 * cmsis_dsp_filter.c - the comparison the firmware page asks for: the
 * paper's filter written the way a firmware author would with Arm's
 * CMSIS-DSP matrix functions (arm_mat_*_f32), on a Cortex-M4F, against the
 * same real sequence as target_test.c. One 6-state filter with 6x6 F, P, Q,
 * 3x6 H, 3x3 R and S, S^-1 by arm_mat_inverse_f32, P = (I - K H) P, R from
 * Eq. 8 with arm_vexp_f32; the paper's settings (hkf_paper_settings, the only
 * thing taken from libhkf), the same loop closure (Eq. 9), yaw wrap
 * and LOST rule. Prints its largest error against the x86 double libhkf
 * build and instructions per update (instruction_counter.h); exits 0 when
 * the errors are within the paper settings' tolerance, which shows both compute the
 * same filter, so that their costs compare.
 */
#include <stdint.h>

#include "arm_math.h"
#include "hkf/hkf.h"
#include "instruction_counter.h"
#include "semihosting.h"
#include "sequence.h"

#define N 6 /* pitch, yaw, roll, and their rates */
#define M 3 /* measured: the angles */

static float wrap180(float x)
{
    while (x >= 180.0f) {
        x -= 360.0f;
    }
    while (x < -180.0f) {
        x += 360.0f;
    }
    return x;
}

typedef struct {
    const hkf_settings_t *s;
    float x[N], p[N * N], center[M];
    float since_measurement;
    int tracking, centred;
} cmsis_filter_t;

/* work matrices, static: the stack holds only frames */
static float f_data[N * N], ft_data[N * N], q_data[N * N], fp_data[N * N], tmp_data[N * N], i_data[N * N];
static float h_data[M * N], ht_data[N * M], pht_data[N * M], s_data[M * M], s_inv_data[M * M], r_data[M * M];
static float k_data[N * M], kh_data[N * N], hx_data[M], y_data[M], ky_data[N], x_new[N];
static arm_matrix_instance_f32 F, Ft, /* 20 instances */ Q, FP, TMP, I6, H, Ht, PHt, S, S_inv, Rm, K, KH, X, Xn, HX, KY, Y, P;

static void matrices_init(cmsis_filter_t *f)
{
    int i;
    arm_mat_init_f32(&F, N, N, f_data);
    arm_mat_init_f32(&Ft, N, N, ft_data);
    arm_mat_init_f32(&Q, N, N, q_data);
    arm_mat_init_f32(&FP, N, N, fp_data);
    arm_mat_init_f32(&TMP, N, N, tmp_data);
    arm_mat_init_f32(&I6, N, N, i_data);
    arm_mat_init_f32(&H, M, N, h_data);
    arm_mat_init_f32(&Ht, N, M, ht_data);
    arm_mat_init_f32(&PHt, N, M, pht_data);
    arm_mat_init_f32(&S, M, M, s_data);
    arm_mat_init_f32(&S_inv, M, M, s_inv_data);
    arm_mat_init_f32(&Rm, M, M, r_data);
    arm_mat_init_f32(&K, N, M, k_data);
    arm_mat_init_f32(&KH, N, N, kh_data);
    arm_mat_init_f32(&X, N, 1, f->x);
    arm_mat_init_f32(&Xn, N, 1, x_new);
    arm_mat_init_f32(&HX, M, 1, hx_data);
    arm_mat_init_f32(&KY, N, 1, ky_data);
    arm_mat_init_f32(&Y, M, 1, y_data);
    arm_mat_init_f32(&P, N, N, f->p);
    for (i = 0; i < N * N; ++i) {
        i_data[i] = (i % (N + 1)) == 0 ? 1.0f : 0.0f;
        f_data[i] = i_data[i];
    }
    for (i = 0; i < M * N; ++i) {
        h_data[i] = (i % (N + 1)) == 0 ? 1.0f : 0.0f;
    }
    arm_mat_trans_f32(&H, &Ht);
}

/* Eq. 8, e(x) = tau - lambda exp(-(x - mu)^2 / (2 sigma^2)), clamped to [r_min, r_max], as R's diagonal */
static void observation_noise(const cmsis_filter_t *f, const float z[M])
{
    float exponent[M], e[M];
    int a;
    for (a = 0; a < M; ++a) {
        const hkf_noise_curve_t *c = &f->s->noise[a];
        const float u = z[a] - c->mu;
        exponent[a] = -(u * u) / (2.0f * c->sigma * c->sigma);
    }
    arm_vexp_f32(exponent, e, M);
    for (a = 0; a < M; ++a) {
        const hkf_noise_curve_t *c = &f->s->noise[a];
        float r = c->tau - c->lambda * e[a];
        r = r < f->s->r_min ? f->s->r_min : r;
        r_data[a * (M + 1)] = r > f->s->r_max ? f->s->r_max : r;
    }
}

static void start_track(cmsis_filter_t *f, const float z[M])
{
    int i;
    for (i = 0; i < N * N; ++i) {
        f->p[i] = 0.0f;
    }
    for (i = 0; i < M; ++i) {
        f->x[i] = i == 1 ? wrap180(z[i]) : z[i];
        f->x[i + M] = 0.0f;
        f->p[i * (N + 1)] = f->s->p0_angle;
        f->p[(i + M) * (N + 1)] = f->s->p0_rate;
    }
    if (!f->centred) {
        f->center[0] = f->x[0];
        f->center[1] = f->x[1];
        f->center[2] = f->x[2];
        f->centred = 1;
    }
    f->since_measurement = 0.0f;
    f->tracking = 1;
}

/* x = F x, P = F P F' + Q for the constant-velocity model */
static void predict(cmsis_filter_t *f, float dt)
{
    int a;
    for (a = 0; a < M; ++a) {
        const float q = f->s->process_noise[a];
        f_data[a * N + a + M] = dt;
        q_data[a * N + a] = q * dt * dt * dt / 3.0f;
        q_data[a * N + a + M] = q_data[(a + M) * N + a] = q * dt * dt / 2.0f;
        q_data[(a + M) * N + a + M] = q * dt;
    }
    arm_mat_mult_f32(&F, &X, &Xn);
    arm_copy_f32(x_new, f->x, N);
    f->x[1] = wrap180(f->x[1]);
    arm_mat_trans_f32(&F, &Ft);
    arm_mat_mult_f32(&F, &P, &FP);
    arm_mat_mult_f32(&FP, &Ft, &TMP);
    arm_mat_add_f32(&TMP, &Q, &P);
}

/* one measurement: returns 0, or 1 when arm_mat_inverse_f32 finds S singular
 * (not inlined, so that dev/benchmarks/cortex_m4_cycles.py finds it) */
__attribute__((noinline)) static int cmsis_filter_update(cmsis_filter_t *f, const float z[M], float dt)
{
    float zc[M], d[M];
    int a;
    if (!f->tracking) {
        observation_noise(f, z);
        start_track(f, z);
        return 0;
    }
    predict(f, dt);
    for (a = 0; a < M; ++a) { /* Eq. 9: within lc_theta of the centre, z = kappa + xi (z - kappa) */
        d[a] = z[a] - f->center[a];
        zc[a] = z[a];
    }
    d[1] = wrap180(d[1]);
    if (f->s->loop_closure == HKF_LOOP_CLOSURE_NORM &&
        d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= f->s->lc_theta * f->s->lc_theta) {
        for (a = 0; a < M; ++a) {
            zc[a] = f->center[a] + f->s->lc_xi * d[a];
        }
        zc[1] = wrap180(zc[1]);
    }
    observation_noise(f, zc);
    arm_mat_mult_f32(&H, &X, &HX); /* Eq. 4: y = z - H x */
    arm_sub_f32(zc, hx_data, Y.pData, M);
    Y.pData[1] = wrap180(Y.pData[1]);
    arm_mat_mult_f32(&P, &Ht, &PHt); /* Eq. 5: S = H P H' + R */
    arm_mat_mult_f32(&H, &PHt, &S);
    arm_mat_add_f32(&S, &Rm, &S);
    if (arm_mat_inverse_f32(&S, &S_inv) != ARM_MATH_SUCCESS) {
        return 1;
    }
    arm_mat_mult_f32(&PHt, &S_inv, &K); /* Eq. 6: K = P H' S^-1 */
    arm_mat_mult_f32(&K, &Y, &KY);       /* Eq. 7: x = x + K y, P = (I - K H) P */
    arm_add_f32(f->x, ky_data, f->x, N);
    f->x[1] = wrap180(f->x[1]);
    arm_mat_mult_f32(&K, &H, &KH);
    arm_mat_sub_f32(&I6, &KH, &KH);
    arm_mat_mult_f32(&KH, &P, &TMP);
    arm_copy_f32(tmp_data, f->p, N * N);
    f->since_measurement = 0.0f;
    return 0;
}

static void cmsis_filter_coast(cmsis_filter_t *f, float dt)
{
    int i;
    if (!f->tracking) {
        return;
    }
    predict(f, dt);
    f->since_measurement += dt;
    if (f->since_measurement >= f->s->coast_time) { /* LOST: rates and their covariances zeroed */
        for (i = 0; i < N * N; ++i) {
            if (i / N >= M || i % N >= M) {
                f->p[i] = 0.0f;
            }
        }
        f->x[3] = f->x[4] = f->x[5] = 0.0f;
        f->tracking = 0;
    }
}

static float angle_error(float a, float b)
{
    const float d = wrap180(a - b);
    return d < 0.0f ? -d : d;
}

/* The largest error per axis, the tolerance, the instructions per update and the memory. */
static void report(const float worst[M], uint32_t ticks, uint32_t updates)
{
    semihosting_write("cmsis_dsp_filter: " SEQ_NAME ", ");
    semihosting_write_int(SEQ_FRAMES);
    semihosting_write(" frames; largest error against the x86 double build: pitch ");
    semihosting_write_int((long)(worst[0] * 1e6f + 0.5f));
    semihosting_write(" udeg, yaw ");
    semihosting_write_int((long)(worst[1] * 1e6f + 0.5f));
    semihosting_write(" udeg, roll ");
    semihosting_write_int((long)(worst[2] * 1e6f + 0.5f));
    semihosting_write(" udeg (tolerance ");
    semihosting_write_int((long)(seq_tolerance_deg[0] * 1e6f + 0.5f));
    semihosting_write(" udeg); cmsis_filter_update: ");
    semihosting_write_int((long)updates);
    semihosting_write(" calls, ");
    semihosting_write_int(counter_instructions_per_call(ticks, updates));
    semihosting_write(" instructions each; sizeof(cmsis_filter_t) ");
    semihosting_write_int((long)sizeof(cmsis_filter_t));
    semihosting_write(" B; work matrices ");
    semihosting_write_int((long)(sizeof f_data + sizeof ft_data + sizeof q_data + sizeof fp_data + sizeof tmp_data +
                                 sizeof i_data + sizeof h_data + sizeof ht_data + sizeof pht_data + sizeof s_data +
                                 sizeof s_inv_data + sizeof r_data + sizeof k_data + sizeof kh_data + sizeof hx_data + sizeof y_data +
                                 sizeof ky_data + sizeof x_new + sizeof F * 20u));
    semihosting_write(" B\n");
}

int main(void)
{
    static cmsis_filter_t filter;
    float worst[M] = {0.0f, 0.0f, 0.0f};
    uint32_t ticks = 0, updates = 0;
    int i, a, failures = 0, started = 0;
    filter.s = &hkf_paper_settings;
    if (filter.s->noise_mode != HKF_NOISE_ADAPTIVE || filter.s->gate_sigma > 0.0f || filter.s->start_rate > 0.0f) {
        semihosting_write("cmsis_dsp_filter: the paper's settings changed (adaptive R, no gate, no motion adaptation expected)\n");
        return 1;
    }
    matrices_init(&filter);
    counter_start();
    for (i = 0; i < SEQ_FRAMES; ++i) {
        if (seq_valid[i]) {
            const float z[M] = {seq_z[i][0], seq_z[i][1], seq_z[i][2]};
            const int was_tracking = filter.tracking;
            const uint32_t start = counter_now();
            failures += cmsis_filter_update(&filter, z, seq_dt[i]);
            if (was_tracking) { /* a filter update, as hkf_update is counted */
                ticks += counter_ticks(start, counter_now());
                ++updates;
            }
            started = 1;
        } else {
            cmsis_filter_coast(&filter, seq_dt[i]);
        }
        if (!started) {
            continue;
        }
        for (a = 0; a < M; ++a) {
            const float e = angle_error(filter.x[a], seq_expected[0][i][a]);
            worst[a] = e > worst[a] ? e : worst[a];
        }
    }
    report(worst, ticks, updates);
    for (a = 0; a < M; ++a) {
        failures += !(worst[a] <= seq_tolerance_deg[0]);
    }
    return failures == 0 ? 0 : 1;
}
