/*
 * flightgear_line.h - the bridge's FlightGear output (hkf-opentrack --flightgear): a pose's six
 * values, as opentrack_pose_values makes them (opentrack's axes and signs, relative to hkf's centre
 * unless --absolute), as one line of FlightGear's generic protocol "hkf"
 * (packaging/flightgear/Protocol/hkf.xml), free of any transport.
 *
 * The line: six numbers separated by commas, then a newline, in the protocol file's order:
 *     heading offset (deg), pitch offset (deg), roll offset (deg), x, y, z (m)
 * which the protocol writes to /sim/current-view/goal-heading-offset-deg, goal-pitch-offset-deg,
 * goal-roll-offset-deg, x-offset-m, y-offset-m and z-offset-m.
 *
 * FlightGear's view conventions (checked against FlightGear 2020.3 itself by ./run flightgear):
 * - a positive heading offset looks left: heading = -yaw (hkf's and opentrack's yaw > 0 looks right);
 * - a positive pitch offset looks up: pitch = pitch (hkf's pitch > 0 is nose up);
 * - a positive roll offset tilts the view clockwise, the right ear down: roll = -opentrack's roll
 *   (opentrack's roll is hkf's with the sign flipped: opentrack_packet.h);
 * - x, y, z are the eye's absolute position in the aircraft, x to the pilot's right, y up, z aft,
 *   in m: the sender adds the aircraft's eye point (--eye X,Y,Z, the view's x/y/z-offset-m at rest).
 *   The head moving to the image's right (hkf's x > 0, the player's left before a camera that does
 *   not mirror) moves the eye left: x = eye x - x; y = eye y + y; z = eye z + z (hkf's z grows away
 *   from the camera, i.e. back from the screen, which is aft).
 * The user's --invert and --scale act before this mapping, on opentrack's axes, as for opentrack.
 */
#ifndef FLIGHTGEAR_LINE_H
#define FLIGHTGEAR_LINE_H

#include <stddef.h>

#include "opentrack_packet.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FLIGHTGEAR_LINE_MAX 160 /* bytes: six numbers of at most 20 characters, commas and the newline */
#define FLIGHTGEAR_DEFAULT_PORT "5550"

/* The six view values for FlightGear from the bridge's six (opentrack_pose_values' order and units) and
 * the aircraft's eye point (m): heading, pitch, roll (deg), x, y, z (m), in the line's order. */
void flightgear_view_values(const double values[OPENTRACK_FIELDS], const double eye[3], double view[6]);

/* The line for view values (flightgear_view_values): its length without the terminating NUL, or -1 when
 * it does not fit in size bytes or a value is not finite (never sent). */
int flightgear_line(const double view[6], char *line, size_t size);

#ifdef __cplusplus
}
#endif

#endif /* FLIGHTGEAR_LINE_H */
