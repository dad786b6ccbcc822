/*
 * pose_csv.h - hkf-filter's --csv output: one line per published pose.
 */
#ifndef POSE_CSV_H
#define POSE_CSV_H

#include <stdio.h>

#include "hkf_head_pose_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Each returns 0, or -1 when the write failed (the file's close must still be checked). */
int pose_csv_write_header(FILE *csv);
int pose_csv_write(FILE *csv, const hkf_head_pose_t *pose);

#ifdef __cplusplus
}
#endif

#endif /* POSE_CSV_H */
