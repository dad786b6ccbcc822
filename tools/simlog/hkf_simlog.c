/*
 * hkf-simlog - writes an LCM log of raw head poses (HEAD_POSE_RAW) from the
 * simulated drive: realistic estimator noise, outliers, frames without a
 * face; seeded, so the same arguments give the same bytes. The input of the
 * log-replay tests and of demos without a camera.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lcm/lcm.h>

#include "arguments.h"
#include "head_motion_sim.h"
#include "hkf_head_pose_measurement_t.h"
#include "lcm_log_writer.h"
#include "safe_files.h"

static void usage(FILE *to)
{
    fprintf(to,
            "usage: hkf-simlog --out FILE [--seconds S] [--seed N] [--fps F] [--model NAME]\n"
            "                  [--start-utime US] [--start-seq N] [--channel C] [--truth CSV]\n"
            "Writes an LCM log of hkf.head_pose_measurement_t from the simulated drive.\n"
            "  --out FILE        the LCM log to write\n"
            "  --seconds S       length, 0.1..36000 s (default 20)\n"
            "  --seed N          noise seed (default 1)\n"
            "  --fps F           camera rate, 1..1000 (default 30)\n"
            "  --model NAME      the measurements' model id (default fsanet)\n"
            "  --start-utime US  capture time of the first frame, us (default 1700000000000000)\n"
            "  --start-seq N     frame counter of the first frame (default 0)\n"
            "  --channel C       channel (default HEAD_POSE_RAW)\n"
            "  --truth CSV       also write the true pose of every frame\n"
            "  --help            this text (--version: the version)\n");
}

static int number_arg(const char *name, const char *text, double low, double high, double *value)
{
    if (!argument_number(text, low, high, value)) {
        fprintf(stderr, "hkf-simlog: %s wants a number from %g to %g, not '%s'\n", name, low, high, text);
        return 0;
    }
    return 1;
}

typedef struct {
    const char *out_path, *truth_path, *channel;
    char *model;
    double seconds, seed, fps, start, start_seq;
} simlog_options_t;

/* The options' values into o. 0: run; 1: --help or --version answered; 2: bad arguments (said). */
static int parse_options(int argc, char **argv, simlog_options_t *o)
{
    int i_arg;
    for (i_arg = 1; i_arg < argc; ++i_arg) {
        const char *arg = argv[i_arg];
        const char *value = i_arg + 1 < argc ? argv[i_arg + 1] : NULL;
        if (argument_help_or_version(arg, "hkf-simlog", usage)) {
            return 1;
        }
        if (value == NULL) {
            fprintf(stderr, "hkf-simlog: unknown or incomplete argument '%s' (see --help)\n", arg);
            return 2;
        }
        ++i_arg;
        if (strcmp(arg, "--out") == 0) {
            o->out_path = value;
        } else if (strcmp(arg, "--truth") == 0) {
            o->truth_path = value;
        } else if (strcmp(arg, "--channel") == 0) {
            o->channel = value;
        } else if (strcmp(arg, "--model") == 0) {
            o->model = argv[i_arg];
        } else if (strcmp(arg, "--seconds") == 0) {
            if (!number_arg(arg, value, 0.1, 36000.0, &o->seconds)) return 2;
        } else if (strcmp(arg, "--seed") == 0) {
            if (!number_arg(arg, value, 0.0, 4294967295.0, &o->seed) || o->seed != floor(o->seed)) return 2;
        } else if (strcmp(arg, "--fps") == 0) {
            if (!number_arg(arg, value, 1.0, 1000.0, &o->fps)) return 2;
        } else if (strcmp(arg, "--start-utime") == 0) {
            if (!number_arg(arg, value, 0.0, 4e18, &o->start)) return 2;
        } else if (strcmp(arg, "--start-seq") == 0) {
            if (!number_arg(arg, value, 0.0, 1e15, &o->start_seq) || o->start_seq != floor(o->start_seq)) return 2;
        } else {
            fprintf(stderr, "hkf-simlog: unknown argument '%s' (see --help)\n", arg);
            return 2;
        }
    }
    if (o->out_path == NULL) {
        fprintf(stderr, "hkf-simlog: --out FILE is required (see --help)\n");
        return 2;
    }
    return 0;
}

/* Frame i of the drive as the estimator would publish it (a fixed face box where a face is seen). */
static hkf_head_pose_measurement_t measurement_of(const sim_frame_t *frame, long i, const simlog_options_t *o)
{
    hkf_head_pose_measurement_t m;
    memset(&m, 0, sizeof m);
    m.utime = (int64_t)o->start + (int64_t)llround(frame->time * 1e6);
    m.seq = (int64_t)o->start_seq + i;
    m.model = o->model;
    m.valid = frame->valid;
    if (frame->valid) {
        m.pitch = (float)frame->measured[0];
        m.yaw = (float)frame->measured[1];
        m.roll = (float)frame->measured[2];
        m.face_box[0] = 180.0f;
        m.face_box[1] = 120.0f;
        m.face_box[2] = 340.0f;
        m.face_box[3] = 320.0f;
        m.detection_score = 0.9f;
    }
    m.inference_us = 8000;
    return m;
}

/* The drive's frames into the log (and their truth into truth, when given). 0, or 1 when a frame could
 * not be encoded (said); a failed write stops the loop and shows at the log's close. */
static int write_frames(const simlog_options_t *o, lcm_log_writer_t *log, FILE *truth, long frames)
{
    sim_config_t config = sim_default_config();
    sim_t sim;
    long i;
    config.fps = o->fps;
    sim_init(&sim, &config, (uint64_t)o->seed);
    for (i = 0; i < frames; ++i) {
        sim_frame_t frame;
        hkf_head_pose_measurement_t m;
        unsigned char buffer[512];
        int size;
        sim_next(&sim, &frame);
        m = measurement_of(&frame, i, o);
        size = hkf_head_pose_measurement_t_encoded_size(&m);
        if (size > (int)sizeof buffer || hkf_head_pose_measurement_t_encode(buffer, 0, size, &m) < 0) {
            fprintf(stderr, "hkf-simlog: cannot encode frame %ld\n", i);
            return 1;
        }
        /* stamped with the capture time: lcm-logplayer paces by it */
        if (lcm_log_writer_write(log, m.utime, o->channel, buffer, size) != 0) {
            return 0; /* reported at the close */
        }
        if (truth != NULL) {
            fprintf(truth, "%lld,%.4f,%.4f,%.4f\n", (long long)m.utime, frame.truth[0], frame.truth[1], frame.truth[2]);
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    simlog_options_t o = {NULL, NULL, "HEAD_POSE_RAW", "fsanet", 20.0, 1.0, 30.0, 1700000000000000.0, 0.0};
    lcm_log_writer_t log;
    FILE *log_file, *truth = NULL;
    long frames;
    int status;
    safe_files_fail_writes_past_size_limit();
    status = parse_options(argc, argv, &o);
    if (status != 0) {
        return status == 1 ? 0 : 2;
    }
    log_file = safe_open_output(o.out_path, "wb", NULL, 0, "hkf-simlog");
    if (log_file == NULL) {
        return 1;
    }
    lcm_log_writer_start(&log, log_file);
    if (o.truth_path != NULL) {
        truth = safe_open_output(o.truth_path, "w", &o.out_path, 1, "hkf-simlog");
        if (truth == NULL) {
            (void)lcm_log_writer_close(&log);
            return 1;
        }
        fprintf(truth, "utime,pitch,yaw,roll\n");
    }
    frames = (long)(o.seconds * o.fps);
    status = write_frames(&o, &log, truth, frames);
    if (lcm_log_writer_close(&log) != 0) {
        fprintf(stderr, "hkf-simlog: error writing '%s' (a full disk?): the log is cut\n", o.out_path);
        status = 1;
    }
    if (truth != NULL && safe_close(truth) != 0) {
        fprintf(stderr, "hkf-simlog: error writing '%s'\n", o.truth_path);
        status = 1;
    }
    if (status == 0) {
        fprintf(stderr, "hkf-simlog: wrote %ld frames (%.1f s at %g fps) to %s\n", frames, o.seconds, o.fps, o.out_path);
    }
    return status;
}
