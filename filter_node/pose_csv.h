/*
 * pose_csv.h - hkf-filter's --csv output: one line per published pose, with its status.
 */
#ifndef POSE_CSV_H
#define POSE_CSV_H

#include <stdio.h>

#include "hkf_head_pose_t.h"
#include "hkf_tracker_status_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Each returns 0, or -1 when the write failed (the file's close must still be checked). A pose's line
 * ends with the status that goes with it (the player's rest: tracker_status_t). */
int pose_csv_write_header(FILE *csv);
int pose_csv_write(FILE *csv, const hkf_head_pose_t *pose, const hkf_tracker_status_t *status);

#ifdef __cplusplus
}
#endif

#endif /* POSE_CSV_H */
