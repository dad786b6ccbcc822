/*
 * opentrack_packet.h - hkf.head_pose_t -> the datagram of opentrack's "UDP over
 * network" input (opentrack's tracker-udp), free of any transport.
 *
 * The datagram: six IEEE-754 doubles, little-endian, 48 bytes, in opentrack's
 * axis order x, y, z (cm), yaw, pitch, roll (deg).
 *
 * Position (hkf 0.2; docs/estimator.md "Head position"): hkf's camera frame, x to the
 * image's right, y up, z away from the camera, sent as it is (opentrack's x,
 * y, z), relative to hkf's centre position unless --absolute; 0 until the
 * filter has a position. Whether a game moves its camera forward for +z or
 * for -z varies: --invert z.
 *
 * Angle convention. hkf (docs/programs.md "Angle convention"): pitch > 0 nose up,
 * yaw > 0 nose to the driver's right, roll > 0 right ear down. opentrack's
 * own face tracker (tracker-neuralnet) builds its angles in a right-handed
 * frame x forward, y up, z to the user's right and publishes yaw and pitch
 * with those signs but roll negated, so in opentrack roll > 0 is LEFT ear
 * down. Hence, once and only here:
 *     opentrack yaw = hkf yaw, opentrack pitch = hkf pitch, opentrack roll = -hkf roll.
 * The user's --invert and --scale apply after this mapping, on opentrack's axes.
 */
#ifndef OPENTRACK_PACKET_H
#define OPENTRACK_PACKET_H

#include "hkf_head_pose_t.h"
#include "hkf_head_pose_v1_t.h"

#ifdef __cplusplus
extern "C" {
#endif

#define OPENTRACK_PACKET_SIZE 48
enum { OPENTRACK_X = 0, OPENTRACK_Y, OPENTRACK_Z, OPENTRACK_YAW, OPENTRACK_PITCH, OPENTRACK_ROLL, OPENTRACK_FIELDS };

/* Which axis a user option names; the index into the arrays below. */
enum {
    OPENTRACK_AXIS_YAW = 0, OPENTRACK_AXIS_PITCH = 1, OPENTRACK_AXIS_ROLL = 2,
    OPENTRACK_AXIS_X = 3, OPENTRACK_AXIS_Y = 4, OPENTRACK_AXIS_Z = 5, OPENTRACK_AXES = 6
};

typedef struct {
    int relative_to_center;       /* send pose - centre (kappa), so RECENTER re-zeroes the game camera */
    int invert[OPENTRACK_AXES];   /* flip the sign of yaw, pitch, roll (after the convention mapping), x, y, z */
    double scale[OPENTRACK_AXES]; /* then multiply */
} opentrack_mapping_t;

/* Relative to the centre, no inversion, scale 1. */
opentrack_mapping_t opentrack_default_mapping(void);

/* "yaw", "pitch", "roll", "x", "y" or "z" -> OPENTRACK_AXIS_*, or -1. */
int opentrack_axis_from_name(const char *name);

/* What no head can do: a pose angle or centre angle beyond this (deg) is a
 * forged or corrupt message, never sent (a turn past it would spin the game
 * camera round). */
#define OPENTRACK_MAX_ABS_ANGLE 180.0
#define OPENTRACK_MAX_ABS_POSITION 1000.0 /* cm: libhkf's HKF_MAX_ABS_POSITION */
#define OPENTRACK_MIN_Z 1.0 /* cm: the nearest z hkf-filter publishes (FILTER_NODE_MIN_Z; 0: not measured) */

/* The six values for one pose: the angles relative to the centre wrapped into
 * [-180, 180), every value scaled and then kept within +-OPENTRACK_MAX_ABS_ANGLE
 * and +-OPENTRACK_MAX_ABS_POSITION. Returns 0; -1 when an angle or the centre
 * is not finite, -2 when one is beyond OPENTRACK_MAX_ABS_ANGLE (neither is ever
 * sent); -3 when the position or its centre is not finite or beyond
 * OPENTRACK_MAX_ABS_POSITION: the angles are in values, the position's three
 * are left as they were (the caller's last); -4 when the status is none that
 * hkf-filter publishes (TRACKING, COASTING, LOST): corrupt, never sent. */
int opentrack_pose_values(const opentrack_mapping_t *mapping, const hkf_head_pose_t *pose,
                          double values[OPENTRACK_FIELDS]);

/* --predict: the pose moved on by its rates for `horizon` s (angles and position), so that a
 * pose sent some time after its capture shows where the head is when it is sent: the angles
 * wrapped into [-180, 180) (a turn past the seam is a turn, not a corrupt pose), z no nearer
 * than OPENTRACK_MIN_Z (a prediction toward the camera stops there, as the filter's coast does).
 * The pose itself when LOST (its rates are 0) or when horizon is not finite or negative. */
hkf_head_pose_t opentrack_predict(const hkf_head_pose_t *pose, double horizon);

/* The horizon of --predict for a pose captured at capture_us and sent at now_us (one wall
 * clock), plus lead_s: 0 (no prediction) when the pose's age is negative or beyond
 * OPENTRACK_MAX_AGE (stamps of another clock: a file read faster than real time, or another
 * machine's), or not a measurement's. */
#define OPENTRACK_MAX_AGE 0.25 /* s: hkf-filter's coast time; an older pose's rate says nothing of now */
double opentrack_horizon(const hkf_head_pose_t *pose, int64_t now_us, double lead_s);

/* The six values as the 48 bytes on the wire (little-endian, whatever the host). */
void opentrack_encode(const double values[OPENTRACK_FIELDS], unsigned char packet[OPENTRACK_PACKET_SIZE]);

#ifdef __cplusplus
}
#endif

#endif /* OPENTRACK_PACKET_H */
