/*
 * pose_csv.c - hkf-filter's --csv output (see pose_csv.h).
 */
#include "pose_csv.h"

int pose_csv_write_header(FILE *csv)
{
    return fprintf(csv, "utime,measurement_utime,seq,status,pitch,yaw,roll,pitch_rate,yaw_rate,roll_rate,"
                 "var_pitch,var_yaw,var_roll,r_pitch,r_yaw,r_roll,loop_closure_active,extrapolated,latency_us,"
                 "x,y,z,x_rate,y_rate,z_rate,var_x,var_y,var_z,center_x,center_y,center_z,position_status,"
                 "rest,rest_progress,rests_spoiled,wander_measured,wander\n") < 0 ? -1 : 0;
}

int pose_csv_write(FILE *csv, const hkf_head_pose_t *p, const hkf_tracker_status_t *s)
{
    if (fprintf(csv, "%lld,%lld,%lld,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%d,%lld,",
                (long long)p->utime, (long long)p->measurement_utime, (long long)p->seq, p->status, (double)p->pitch,
                (double)p->yaw, (double)p->roll, (double)p->pitch_rate, (double)p->yaw_rate, (double)p->roll_rate,
                (double)p->variance[0], (double)p->variance[1], (double)p->variance[2], (double)p->r[0], (double)p->r[1],
                (double)p->r[2], p->loop_closure_active, p->extrapolated, (long long)p->latency_us) < 0) {
        return -1;
    }
    /* the position: cm, cm/s, cm^2, its status */
    if (fprintf(csv, "%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,", (double)p->x, (double)p->y,
                   (double)p->z, (double)p->x_rate, (double)p->y_rate, (double)p->z_rate, (double)p->position_variance[0],
                   (double)p->position_variance[1], (double)p->position_variance[2], (double)p->position_center[0],
                   (double)p->position_center[1], (double)p->position_center[2], p->position_status) < 0) {
        return -1;
    }
    /* the player's rest: what it is doing, its progress, the rests spoiled, HOLD's wander (deg^2) */
    return fprintf(csv, "%d,%.3f,%d,%d,%.6g\n", s->rest, (double)s->rest_progress, (int)s->rests_spoiled,
                   s->wander_measured, (double)s->wander) < 0 ? -1 : 0;
}
