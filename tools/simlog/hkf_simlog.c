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

int main(int argc, char **argv)
{
    const char *out_path = NULL, *truth_path = NULL, *channel = "HEAD_POSE_RAW";
    char *model = "fsanet";
    double seconds = 20.0, seed = 1.0, fps = 30.0, start = 1700000000000000.0, start_seq = 0.0;
    sim_config_t config = sim_default_config();
    sim_t sim;
    lcm_log_writer_t log;
    FILE *log_file;
    FILE *truth = NULL;
    long frames, i;
    int i_arg, status = 0;
    safe_files_fail_writes_past_size_limit();

    for (i_arg = 1; i_arg < argc; ++i_arg) {
        const char *arg = argv[i_arg];
        const char *value = i_arg + 1 < argc ? argv[i_arg + 1] : NULL;
        if (argument_help_or_version(arg, "hkf-simlog", usage)) {
            return 0;
        }
        if (value == NULL) {
            fprintf(stderr, "hkf-simlog: unknown or incomplete argument '%s' (see --help)\n", arg);
            return 2;
        }
        ++i_arg;
        if (strcmp(arg, "--out") == 0) {
            out_path = value;
        } else if (strcmp(arg, "--truth") == 0) {
            truth_path = value;
        } else if (strcmp(arg, "--channel") == 0) {
            channel = value;
        } else if (strcmp(arg, "--model") == 0) {
            model = argv[i_arg];
        } else if (strcmp(arg, "--seconds") == 0) {
            if (!number_arg(arg, value, 0.1, 36000.0, &seconds)) return 2;
        } else if (strcmp(arg, "--seed") == 0) {
            if (!number_arg(arg, value, 0.0, 4294967295.0, &seed) || seed != floor(seed)) return 2;
        } else if (strcmp(arg, "--fps") == 0) {
            if (!number_arg(arg, value, 1.0, 1000.0, &fps)) return 2;
        } else if (strcmp(arg, "--start-utime") == 0) {
            if (!number_arg(arg, value, 0.0, 4e18, &start)) return 2;
        } else if (strcmp(arg, "--start-seq") == 0) {
            if (!number_arg(arg, value, 0.0, 1e15, &start_seq) || start_seq != floor(start_seq)) return 2;
        } else {
            fprintf(stderr, "hkf-simlog: unknown argument '%s' (see --help)\n", arg);
            return 2;
        }
    }
    if (out_path == NULL) {
        fprintf(stderr, "hkf-simlog: --out FILE is required (see --help)\n");
        return 2;
    }
    log_file = safe_open_output(out_path, "wb", NULL, 0, "hkf-simlog");
    if (log_file == NULL) {
        return 1;
    }
    lcm_log_writer_start(&log, log_file);
    if (truth_path != NULL) {
        truth = safe_open_output(truth_path, "w", &out_path, 1, "hkf-simlog");
        if (truth == NULL) {
            (void)lcm_log_writer_close(&log);
            return 1;
        }
        fprintf(truth, "utime,pitch,yaw,roll\n");
    }

    config.fps = fps;
    sim_init(&sim, &config, (uint64_t)seed);
    frames = (long)(seconds * fps);
    for (i = 0; i < frames; ++i) {
        sim_frame_t frame;
        hkf_head_pose_measurement_t m;
        unsigned char buffer[512];
        int size;
        sim_next(&sim, &frame);
        memset(&m, 0, sizeof m);
        m.utime = (int64_t)start + (int64_t)llround(frame.time * 1e6);
        m.seq = (int64_t)start_seq + i;
        m.model = model;
        m.valid = frame.valid;
        if (frame.valid) {
            m.pitch = (float)frame.measured[0];
            m.yaw = (float)frame.measured[1];
            m.roll = (float)frame.measured[2];
            m.face_box[0] = 180.0f;
            m.face_box[1] = 120.0f;
            m.face_box[2] = 340.0f;
            m.face_box[3] = 320.0f;
            m.detection_score = 0.9f;
        }
        m.inference_us = 8000;
        size = hkf_head_pose_measurement_t_encoded_size(&m);
        if (size > (int)sizeof buffer || hkf_head_pose_measurement_t_encode(buffer, 0, size, &m) < 0) {
            fprintf(stderr, "hkf-simlog: cannot encode frame %ld\n", i);
            status = 1;
            break;
        }
        /* stamped with the capture time: lcm-logplayer paces by it */
        if (lcm_log_writer_write(&log, m.utime, channel, buffer, size) != 0) {
            break; /* reported at the close */
        }
        if (truth != NULL) {
            fprintf(truth, "%lld,%.4f,%.4f,%.4f\n", (long long)m.utime, frame.truth[0], frame.truth[1], frame.truth[2]);
        }
    }
    if (lcm_log_writer_close(&log) != 0) {
        fprintf(stderr, "hkf-simlog: error writing '%s' (a full disk?): the log is cut\n", out_path);
        status = 1;
    }
    if (truth != NULL && safe_close(truth) != 0) {
        fprintf(stderr, "hkf-simlog: error writing '%s'\n", truth_path);
        status = 1;
    }
    if (status == 0) {
        fprintf(stderr, "hkf-simlog: wrote %ld frames (%.1f s at %g fps) to %s\n", frames, seconds, fps, out_path);
    }
    return status;
}
