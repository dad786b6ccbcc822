/*
 * hkf_rest.h - the player's rest, measured: an optional part beside the angle filter (not in the
 * paper; libhkf 1.2). While the player looks at the screen's centre and keeps still (about 2 s, at
 * start-up and at every recentre), it measures per axis the frame noise n and the rate q at which the
 * resting estimate wanders, and from them HOLD's wander w (hkf_set_wander), so that a resting view is
 * kept still by a wander measured on this camera, this light and this player, not by a constant.
 *
 * The model: a resting estimate is a rest angle that drifts as a random walk, r_k - r_k-1 ~ N(0, q dt),
 * plus white frame noise e_k ~ N(0, n). Measurements L frames apart then differ by
 *     gamma(L) = E[(z_k+L - z_k)^2] = 2 n + q dt L            (the variogram of a local-level process),
 * a line in L: its intercept gives n, its slope q. The rest's gamma(L) for L = 1..HKF_REST_LAGS (the
 * few-frame scales where a resting estimate wanders) is fitted by least squares.
 *
 * HOLD (hkf.h, the motion adaptation) takes a resting measurement as the held angle plus R plus its
 * wander w. Over the rest, measurements spread about their mean by V; R is the frame noise n; so
 *     w = stillness max over the axes of (V - n),
 * the spread the rest shows beyond its frame noise (for a random walk over a rest of T s, q T / 6), times
 * the player's stillness (1: the measured wander). One w for the three axes, as still_wander is: 2 s
 * under-samples an axis that wandered little in them (docs/libhkf.md gives the figures per axis). White
 * noise alone gives w near 0, and a camera whose rest does not wander keeps raw's onset.
 *
 * Two measurements in a row further from the rest's mean so far than `rest_reach` beyond three standard
 * deviations of the frame noise (a move) spoil the rest: it is not taken, and the measurement starts again
 * from the second (HKF_REST_SPOILED). One alone is an outlier: skipped, not taken. A rest whose spread beyond
 * its noise exceeds (rest_reach / 2)^2 (a slow move, each frame within the reach) is spoiled when it ends.
 *
 * A rest is a rest (libhkf 1.3): a head that sways, talks or settles keeps every frame within the reach, but
 * it moves. When the rest ends, a spread beyond the noise over HKF_REST_MOVED_WANDER or a wander's rate q over
 * HKF_REST_MOVED_DRIFT on any axis is such a head: the rest is refused (HKF_REST_SPOILED, counted in
 * `refused` too) and measured again; until one is taken the filter keeps its built-in still_wander. The
 * measured wander is bounded at HKF_REST_MAX_WANDER, where the filter still shows a 2 deg glance within a
 * frame of raw, before stillness scales it. docs/libhkf.md gives the evidence for the three.
 *
 *     hkf_rest_t rest;  hkf_rest_result_t found;
 *     hkf_rest_init(&rest, &hkf_default_rest_settings);
 *     at start-up and at every recentre:  hkf_rest_start(&rest);
 *     each frame with a face:  if (hkf_rest_update(&rest, z, dt) == HKF_REST_MEASURED) {
 *                                  hkf_rest_get_result(&rest, &found);
 *                                  hkf_set_wander(&f, found.wander);  hkf_set_center(&f, found.center); }
 *     each frame without one:  hkf_rest_update(&rest, NULL, dt);
 * Static memory; float, double or Q16.16 like the rest of libhkf. It runs only while a rest is
 * measured: otherwise hkf_rest_update returns at once.
 */
#ifndef HKF_REST_H
#define HKF_REST_H

#include "hkf/hkf.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The variogram's lags: 1..6 frames (0.2 s at 30 fps), where resting estimates were seen to wander
 * (dev/eval/adaptation_study/README.md). */
#define HKF_REST_LAGS 6
#define HKF_MAX_STILLNESS 100 /* the largest multiple of the measured wander */
#define HKF_REST_MOVE_FRAMES 2 /* frames in a row beyond the reach that are a move (one alone: an outlier, skipped) */
/* deg^2: the most of a rest's spread beyond its noise that HOLD takes as wander: with more, a 2 deg glance is
 * shown two frames or more after raw shows it (30 fps, the noise of real rests; docs/libhkf.md). */
#define HKF_REST_MAX_WANDER 0.3
/* deg^2 and deg^2/s: a rest's spread beyond its noise, or its wander's rate, above which it was a head that
 * moved (the clips' longest still stretches: 0.21-0.45 deg^2 and 0.3-4.1 deg^2/s; heads that moved through
 * their start-up "rest": 0.63-2.2 deg^2 or 4.5-30 deg^2/s; docs/libhkf.md) */
#define HKF_REST_MOVED_WANDER 0.6
#define HKF_REST_MOVED_DRIFT 5.0

typedef struct {
    hkf_real_t rest_time; /* s: how long a rest is measured, within [0, HKF_MAX_TIME]; 0 = off (none is asked for) */
    hkf_real_t rest_reach;     /* deg: further from the rest's mean than this (beyond 3 sigma of noise) is a move, within (0, HKF_MAX_LC_THETA] */
    hkf_real_t stillness; /* HOLD's wander as a multiple of the measured one, within [0, HKF_MAX_STILLNESS] */
} hkf_rest_settings_t;

/* rest_time 2 s, rest_reach 3 deg, stillness 1. */
extern const hkf_rest_settings_t hkf_default_rest_settings;

/* What one hkf_rest_update did. */
typedef enum {
    HKF_REST_IDLE = 0,      /* no rest is being measured */
    HKF_REST_MEASURING = 1, /* the measurement was taken into the rest */
    HKF_REST_MEASURED = 2,  /* ... and completed it: hkf_rest_get_result has the result */
    HKF_REST_SPOILED = 3    /* it was a move: the rest so far is dropped, and measured again from it */
} hkf_rest_event_t;

/* A measured rest. */
typedef struct {
    hkf_real_t center[3]; /* deg: the rest's mean pose (yaw in [-180, 180)) */
    hkf_real_t noise[3];  /* deg^2: the frame noise n */
    hkf_real_t drift[3];  /* deg^2/s: the wander's rate q */
    hkf_real_t spread[3]; /* deg^2: the rest's variance about its mean */
    hkf_real_t wander;    /* deg^2: HOLD's wander w, stillness x the measured one (for hkf_set_wander) */
    hkf_real_t period;    /* s: the rest's mean frame period dt */
} hkf_rest_result_t;

/* Private: members may change between versions. */
typedef struct {
    hkf_rest_settings_t settings;
    int measuring;                 /* a rest is being measured */
    int measured;                  /* a result is held */
    unsigned frames;               /* measurements in this rest */
    unsigned history;              /* measurements in a row in `recent` (0..HKF_REST_LAGS) */
    unsigned beyond;               /* measurements in a row beyond the reach */
    unsigned spoiled;              /* rests spoiled since hkf_rest_start (refused ones too) */
    unsigned refused;              /* of those, rests refused at their end as a head that moved */
    hkf_rest_result_t last_refused; /* what the last refused rest measured */
    unsigned pairs[HKF_REST_LAGS]; /* measurement pairs L + 1 frames apart so far */
    hkf_real_t elapsed;            /* s: the rest's time so far (frames with a measurement) */
    hkf_real_t period;             /* s: the mean time between consecutive measurements */
    hkf_real_t origin[3];          /* deg: the rest's first measurement; the values below are from it */
    hkf_real_t mean[3];            /* deg: the rest's mean */
    hkf_real_t square[3];          /* deg^2: the rest's mean square */
    hkf_real_t recent[HKF_REST_LAGS][3];   /* deg: the last measurements, recent[0] the newest */
    hkf_real_t gamma[HKF_REST_LAGS][3];    /* deg^2: the mean squared difference L + 1 frames apart */
    hkf_rest_result_t result;
} hkf_rest_t;

/* Checks the settings (HKF_ERROR_SETTING_REST, HKF_ERROR_SETTING_NON_FINITE, HKF_ERROR_NULL_ARGUMENT)
 * and starts idle, with no result. */
int hkf_rest_init(hkf_rest_t *r, const hkf_rest_settings_t *s);

/* A rest begins (none with rest_time 0): the player is asked to keep still. Forgets any rest in progress and the count of
 * spoiled ones; keeps the last result until a new one completes. */
int hkf_rest_start(hkf_rest_t *r);

/* Stops measuring (the result, if any, is kept). */
int hkf_rest_stop(hkf_rest_t *r);

/* One frame: z the raw measurement (NULL: none this frame; it breaks the differences), dt the time
 * since the previous frame (ignored for a rest's first measurement). Returns a hkf_rest_event_t, or a
 * negative hkf_result_t (HKF_ERROR_NON_FINITE, HKF_ERROR_DT_RANGE: dt <= 0 or > HKF_MAX_TIME,
 * HKF_ERROR_ANGLE_RANGE), which changes nothing. */
int hkf_rest_update(hkf_rest_t *r, const hkf_real_t z[3], hkf_real_t dt);

/* Where the rest stands: measuring (1) or not (0), its progress 0..1 (rest time so far over rest_time),
 * the rests spoiled since hkf_rest_start, and whether a result is held. Any pointer may be NULL. */
int hkf_rest_get_progress(const hkf_rest_t *r, int *measuring, hkf_real_t *progress, unsigned *spoiled,
                          int *measured);

/* The last completed rest's result: HKF_ERROR_NOT_INITIALIZED before any. */
int hkf_rest_get_result(const hkf_rest_t *r, hkf_rest_result_t *result);

/* The player's stillness changed while tracking (libhkf 1.3): the settings take it, and the held result's
 * wander becomes stillness x its measured one, as if the rest had ended with it (give it to hkf_set_wander).
 * HKF_ERROR_SETTING_REST (outside [0, HKF_MAX_STILLNESS]), HKF_ERROR_SETTING_NON_FINITE or
 * HKF_ERROR_NULL_ARGUMENT change nothing. */
int hkf_rest_set_stillness(hkf_rest_t *r, hkf_real_t stillness);

#ifdef __cplusplus
}
#endif

#endif /* HKF_REST_H */
