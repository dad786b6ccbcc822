"""The player's start-up rest, for the evaluations (the rest issue; libhkf's hkf_rest.h, hkf-filter's node_rest.h).

A player is asked to look at the screen's centre and keep still for 2 s when tracking starts. A shared clip has
no such rest at its start, so each clip's own longest rest stands in for it: the same camera, light and person.
A rest here is the longest stretch of the clip whose head pose, the evaluation's zero-phase reference
(metrics.reference), stays within +-REST_HALF_WIDTH deg on every axis; its first REST_MAX_S at most; none when it
is shorter than REST_MIN_S. It is chosen from the reference, not from hkf's own test, so that hkf does not pick
its own rest.

with_rest writes a log that plays that rest first, then, after a gap longer than hkf-filter's max_dt (the track
restarts: the clip is filtered from its start, with the rest's wander and centre), the whole clip. hkf-filter
measures the rest in rest_time = the rest's length (REST_SETTING). Truth clips (truth_clips.py) are made with
a 2 s hold at their start instead, and need none of this.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import metrics  # noqa: E402

REST_HALF_WIDTH = 1.0  # deg: the reference stays within this of its middle on every axis
REST_MIN_S = 1.0       # s: a shorter rest is none
REST_MAX_S = 2.0       # s: what hkf-filter asks a player for (hkf_default_rest_settings.rest_time)
GAP_S = 1.5            # s between the rest and the clip: beyond max_dt (1 s), so the track restarts


def rest_window(t, valid, z):
    """(first, end) indices into the valid frames of the clip's rest, or None (no rest of REST_MIN_S)."""
    tv = t[valid]
    ref = metrics.reference(tv, z[valid])
    best, best_length, first = (0, 1), -1.0, 0
    for end in range(1, len(tv) + 1):
        while (np.ptp(ref[first:end], axis=0) > 2 * REST_HALF_WIDTH).any():
            first += 1
        if tv[end - 1] - tv[first] > best_length:
            best, best_length = (first, end), tv[end - 1] - tv[first]
    first, end = best
    while end - first > 2 and tv[end - 1] - tv[first] > REST_MAX_S:
        end -= 1
    return (first, end) if tv[end - 1] - tv[first] >= REST_MIN_S else None


def rest_setting(t, valid, window):
    """hkf-filter's --set for the rest of this window: rest_time its length, a frame short of it (the node
    completes a rest to the nearest frame)."""
    tv = t[valid]
    first, end = window
    return f"rest_time={tv[end - 1] - tv[first] - 0.4 * np.median(np.diff(tv)):.4f}"


def with_rest(source, path, types_dir, utime, valid, window):
    """Writes PATH: the rest's HEAD_POSE_RAW messages of SOURCE first (re-stamped to end GAP_S before the clip's
    first frame, numbered before it), then every event of SOURCE as it was."""
    import lcm
    sys.path.insert(0, types_dir)
    from hkf import head_pose_measurement_t
    rest_utimes = set(int(u) for u in utime[valid][window[0]:window[1]])
    events = [e for e in lcm.EventLog(source, "r")]
    raw = [e for e in events if e.channel == "HEAD_POSE_RAW"]
    first = head_pose_measurement_t.decode(raw[0].data)
    rest = [(e, m) for e, m in ((e, head_pose_measurement_t.decode(e.data)) for e in raw) if m.utime in rest_utimes]
    shift = first.utime - int(GAP_S * 1e6) - rest[-1][1].utime
    out = lcm.EventLog(path, "w", overwrite=True)
    for k, (event, m) in enumerate(rest):
        m.utime += shift
        m.seq = first.seq - len(rest) - 1 + k
        out.write_event(event.timestamp + shift, event.channel, m.encode())
    for event in events:
        out.write_event(event.timestamp, event.channel, event.data)
    out.close()
