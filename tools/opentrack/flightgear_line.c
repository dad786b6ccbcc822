/* flightgear_line.c - see flightgear_line.h. */
#include "flightgear_line.h"

#include <math.h>
#include <stdio.h>

void flightgear_view_values(const double values[OPENTRACK_FIELDS], const double eye[3], double view[6])
{
    view[0] = -values[OPENTRACK_YAW];  /* FlightGear's heading offset > 0 looks left */
    view[1] = values[OPENTRACK_PITCH]; /* its pitch offset > 0 looks up, as hkf's pitch */
    view[2] = -values[OPENTRACK_ROLL]; /* its roll offset > 0 is the right ear down: hkf's roll, opentrack's negated */
    view[3] = eye[0] - values[OPENTRACK_X] * 0.01; /* cm -> m; the image's right is the player's left */
    view[4] = eye[1] + values[OPENTRACK_Y] * 0.01;
    view[5] = eye[2] + values[OPENTRACK_Z] * 0.01; /* away from the camera: aft */
}

int flightgear_line(const double view[6], char *line, size_t size)
{
    int i, n;
    for (i = 0; i < 6; ++i) {
        if (!isfinite(view[i])) {
            return -1;
        }
    }
    /* %.4f: 0.0001 deg and 0.1 mm, finer than FlightGear's read-back check (0.05 deg, 0.1 mm) needs */
    n = snprintf(line, size, "%.4f,%.4f,%.4f,%.5f,%.5f,%.5f\n", view[0], view[1], view[2], view[3], view[4], view[5]);
    return n > 0 && (size_t)n < size ? n : -1;
}
