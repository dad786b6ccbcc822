/*
 * head_motion_sim.h - simulated driver head motion with estimator-like noise.
 *
 * The built-in input of the demo and the source of test and replay data: a
 * scripted drive (looking ahead, mirror glances, a shoulder check, nods and
 * tilts) sampled by a camera, with the errors a deep head-pose estimator makes:
 * white noise whose size follows the FSA-Net error curves of the paper's
 * Table I, a slowly drifting bias, occasional outliers, and bursts of frames
 * without a face. Seeded and deterministic. Angles in degrees (pitch, yaw,
 * roll), times in seconds.
 */
#ifndef HEAD_MOTION_SIM_H
#define HEAD_MOTION_SIM_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* A small deterministic random generator (xorshift64*). */
typedef struct { uint64_t state; } sim_rng_t;
void sim_rng_seed(sim_rng_t *rng, uint64_t seed);
double sim_rng_uniform(sim_rng_t *rng);   /* [0, 1) */
double sim_rng_gaussian(sim_rng_t *rng);  /* N(0, 1) */

/* The scripted head pose at time t (the script repeats every
 * sim_script_period() seconds). */
void sim_head_pose(double t, double pose[3]);
double sim_script_period(void);

typedef struct {
    double fps;              /* camera frames per second */
    double noise_scale;      /* 1 = FSA-Net-like error; 0 = perfect measurements */
    double outlier_rate;     /* probability of an outlier frame */
    double dropout_rate;     /* probability that a burst without a face starts */
    double dropout_max_s;    /* longest burst without a face, s */
    double frame_jitter_s;   /* standard deviation of the capture-time jitter, s */
} sim_config_t;

/* 30 fps, FSA-Net-like noise, 0.5 % outliers, rare dropouts up to 0.4 s. */
sim_config_t sim_default_config(void);

typedef struct {
    double time;        /* capture time, s */
    double truth[3];    /* true pose */
    double measured[3]; /* what the estimator reports; meaningful when valid */
    int valid;          /* 0: no face in this frame */
    int still;          /* 1: the true head is not moving */
} sim_frame_t;

typedef struct {
    sim_config_t config;
    sim_rng_t rng;
    long frame;
    double bias[3];
    int dropout_frames_left;
} sim_t;

void sim_init(sim_t *sim, const sim_config_t *config, uint64_t seed);
void sim_next(sim_t *sim, sim_frame_t *out);

#ifdef __cplusplus
}
#endif

#endif /* HEAD_MOTION_SIM_H */
