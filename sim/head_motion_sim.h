/*
 * head_motion_sim.h - simulated driver head motion with estimator-like noise.
 *
 * The built-in input of the demo and the source of test and replay data: a
 * scripted drive (looking ahead, mirror glances, a shoulder check, nods and
 * tilts) sampled by a camera, with the errors a deep head-pose estimator makes,
 * sized by the FSA-Net error curves of the paper's Table I: as measured on our
 * real clips (a little white frame noise, the rest a bias that follows the
 * pose), or as first assumed (much white noise, a drifting bias, outliers);
 * and bursts of frames without a face. Seeded and deterministic. Angles in degrees (pitch, yaw,
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
/* 1 if the scripted head turns slower than 1 deg/s at time t. */
int sim_head_still(double t);

/* How the simulated estimator errs (head_motion_sim.c says where each figure comes from). */
typedef enum {
    SIM_ERRORS_MEASURED = 0, /* as our estimators measure on real clips: white frame noise of 0.25 deg,
                                the rest of the FSA-Net-sized error a bias that follows the pose */
    SIM_ERRORS_ASSUMED = 1   /* the first assumption: 30 % of the error variance white, the rest a bias
                                drifting over 1 s whatever the pose */
} sim_error_model_t;

typedef struct {
    double fps;              /* camera frames per second */
    int error_model;         /* a sim_error_model_t */
    double noise_scale;      /* 1 = FSA-Net-like error; 0 = perfect measurements */
    double outlier_rate;     /* probability of an outlier frame */
    double dropout_rate;     /* probability that a burst without a face starts */
    double dropout_max_s;    /* longest burst without a face, s */
    double frame_jitter_s;   /* standard deviation of the capture-time jitter, s */
} sim_config_t;

/* 30 fps, the measured error model with FSA-Net-sized errors, no outliers,
 * rare dropouts up to 0.4 s. */
sim_config_t sim_default_config(void);
/* The same with the first assumed errors: 30 % white, 0.5 % outliers. */
sim_config_t sim_assumed_config(void);

typedef struct {
    double time;        /* capture time, s */
    double truth[3];    /* true pose */
    double measured[3]; /* what the estimator reports; meaningful when valid */
    int valid;          /* 0: no face in this frame */
    int still;          /* 1: the true head is not moving */
} sim_frame_t;

enum { SIM_BIAS_WAVES = 4 };

typedef struct {
    sim_config_t config;
    sim_rng_t rng;
    long frame;
    double bias[3];
    /* the measured model's bias field: per axis, a sum of plane waves over the pose */
    double wave_direction[3][SIM_BIAS_WAVES][3];
    double wave_number[3][SIM_BIAS_WAVES]; /* rad per deg */
    double wave_phase[3][SIM_BIAS_WAVES];
    int dropout_frames_left;
} sim_t;

void sim_init(sim_t *sim, const sim_config_t *config, uint64_t seed);
void sim_next(sim_t *sim, sim_frame_t *out);

#ifdef __cplusplus
}
#endif

#endif /* HEAD_MOTION_SIM_H */
