"""Prototype: GPB1 two-mode adaptation vs 1 euro on the truth clips (roll only), vectorised over settings."""
import os, sys, itertools, pickle, glob
import numpy as np
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import evaluate, truth_eval, truth_metrics, truth_clips

BUILD = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "build"); OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "out", "eval")
ROLL = 2
TAU, LAM, MU, SIG = 29.637, 27.126, 0.94, 34.82  # mesh_pnp roll curve

def e_curve(x):
    return (TAU - LAM) + LAM * (1 - np.exp(-(x - MU) ** 2 / (2 * SIG * SIG)))

def load_clips():
    specs = []
    for log_path in sorted(glob.glob(os.path.join(OUT, "truth", "clips", "*_f*.lcmlog"))):
        label = os.path.basename(log_path)[:-7]
        name = label.split("_")[0]
        clip = [c for c in evaluate.clips() if os.path.basename(c).startswith(name + ".")][0]
        specs.append((label, name, clip, log_path))
    clips = []
    for label, name, clip, log_path in specs:
        # rebuild spec like make_still_clips without remaking
        import zlib, truth_motion
        raw = evaluate.raw_log(BUILD, OUT, clip, truth_eval.ESTIMATOR)
        utime, valid, z, centres = truth_eval.read_raw_with_boxes(raw, os.path.join(BUILD, "lcmtypes", "python"))
        index = int(label.split("_f")[1])
        img_shape = truth_clips.read_frames(clip, [0])[0].shape
        seed = zlib.crc32(label.encode())
        trajectory = truth_motion.driver_trajectory(seed, truth_eval.FPS, 4)
        axis = truth_clips.line_of_sight(centres[index], (img_shape[1], img_shape[0]))
        clips.append(truth_eval.load((label, name, "still frame", trajectory, log_path, [axis]), BUILD))
    return clips

def noise_level(t, valid, z, time=0.3, rise=0.2, r_min=1e-6):
    """the calibration's n per frame (before that frame's update), as libhkf's."""
    n = e_curve(MU); power = n
    out = np.empty(len(t)); hist = 0; last_z = last_step = 0.0; last_t = None
    for i in range(len(t)):
        out[i] = n
        if not valid[i]:
            hist = 0; continue
        dt = t[i] - last_t if last_t is not None else 1 / 30
        last_t = t[i]
        step = z[i] - last_z
        if hist >= 2:
            beta = min(dt / (dt + time), 1.0)
            d = step - last_step
            nxt = power + beta * (d * d / 6 - power)
            est = min(n * (1 + rise * dt), nxt)
            power = nxt; n = max(est, r_min)
        last_z, last_step = z[i], step
        hist = min(hist + 1, 2)
    return out

def gpb1(t, valid, z, R, qs, qm, a, b, p0=(1.0, 100.0), still_rate_zero=False):
    """vectorised over setting arrays qs, qm, a, b (same shape)."""
    k = qs.shape
    x = np.zeros(k); v = np.zeros(k); P00 = np.full(k, p0[0]); P01 = np.zeros(k); P11 = np.full(k, p0[1]); mu = np.zeros(k)
    out = np.full((len(t),) + k, np.nan); started = False; last_t = None
    for i in range(len(t)):
        if not valid[i]:
            if started:
                out[i] = x
            continue
        if not started:
            x[:] = z[i]; started = True; last_t = t[i]; out[i] = x; continue
        dt = t[i] - last_t; last_t = t[i]
        pi = mu * (1 - b * dt) + (1 - mu) * a * dt
        xp = x + v * dt
        B00 = P00 + dt * (2 * P01 + dt * P11); B01 = P01 + dt * P11; B11 = P11
        q3, q2, q1 = dt ** 3 / 3, dt ** 2 / 2, dt
        Ps = (B00 + qs * q3, B01 + qs * q2, B11 + qs * q1)
        Pm = (B00 + qm * q3, B01 + qm * q2, B11 + qm * q1)
        y = z[i] - xp
        Ss = Ps[0] + R[i]; Sm = Pm[0] + R[i]
        llr = 0.5 * np.log(Ss / Sm) - 0.5 * y * y * (1 / Sm - 1 / Ss)
        lo = np.log(np.maximum(pi, 1e-12) / np.maximum(1 - pi, 1e-12)) + llr
        mu = 1 / (1 + np.exp(-np.clip(lo, -50, 50)))
        Ks0, Ks1 = Ps[0] / Ss, Ps[1] / Ss
        Km0, Km1 = Pm[0] / Sm, Pm[1] / Sm
        K0 = mu * Km0 + (1 - mu) * Ks0; K1 = mu * Km1 + (1 - mu) * Ks1
        # posterior covariances of each mode
        s00 = (1 - Ks0) * Ps[0]; s01 = (1 - Ks0) * Ps[1]; s11 = Ps[2] - Ks1 * Ps[1]
        m00 = (1 - Km0) * Pm[0]; m01 = (1 - Km0) * Pm[1]; m11 = Pm[2] - Km1 * Pm[1]
        d0 = (Km0 - Ks0) * y; d1 = (Km1 - Ks1) * y; w = mu * (1 - mu)
        P00 = mu * m00 + (1 - mu) * s00 + w * d0 * d0
        P01 = mu * m01 + (1 - mu) * s01 + w * d0 * d1
        P11 = mu * m11 + (1 - mu) * s11 + w * d1 * d1
        x = xp + K0 * y; v = v + K1 * y
        out[i] = x
    return out

def one_euro(t, valid, z, mc, beta, dcut=1.0):
    k = mc.shape
    x = None; dx = np.zeros(k); out = np.full((len(t),) + k, np.nan); last_t = None
    for i in range(len(t)):
        if not valid[i]:
            if x is not None: out[i] = x
            continue
        if x is None:
            x = np.full(k, z[i]); last_t = t[i]; out[i] = x; continue
        dt = max(t[i] - last_t, 1e-6); last_t = t[i]
        step = z[i] - x
        ad = 1 / (1 + 1 / (2 * np.pi * dcut * dt))
        dx = dx + ad * (step / dt - dx)
        cut = mc + beta * np.abs(dx)
        al = 1 / (1 + 1 / (2 * np.pi * cut * dt))
        x = x + al * step
        out[i] = x
    return out

def gpb1_hold(t, valid, z, R, qs, qm, a, b, p0=(1.0, 100.0)):
    """GPB1 with a still model (angle random walk qs deg^2/s, rate 0) and a moving CV model (qm deg^2/s^3)."""
    k = qs.shape
    x = np.zeros(k); v = np.zeros(k); P00 = np.full(k, p0[0]); P01 = np.zeros(k); P11 = np.full(k, p0[1]); mu = np.zeros(k)
    out = np.full((len(t),) + k, np.nan); started = False; last_t = None
    mus = np.full((len(t),) + k, np.nan)
    for i in range(len(t)):
        if not valid[i]:
            if started:
                out[i] = x
            continue
        if not started:
            x[:] = z[i]; started = True; last_t = t[i]; out[i] = x; continue
        dt = t[i] - last_t; last_t = t[i]
        pi = mu * (1 - b * dt) + (1 - mu) * a * dt
        # still: angle held, rate 0
        s00 = P00 + qs * dt
        ys = z[i] - x
        Ss = s00 + R[i]
        # moving: constant velocity
        m00 = P00 + dt * (2 * P01 + dt * P11) + qm * dt ** 3 / 3
        m01 = P01 + dt * P11 + qm * dt ** 2 / 2
        m11 = P11 + qm * dt
        ym = z[i] - (x + v * dt)
        Sm = m00 + R[i]
        llr = 0.5 * np.log(Ss / Sm) - 0.5 * (ym * ym / Sm - ys * ys / Ss)
        lo = np.log(np.maximum(pi, 1e-12) / np.maximum(1 - pi, 1e-12)) + llr
        mu = 1 / (1 + np.exp(-np.clip(lo, -50, 50)))
        # posteriors
        ks = s00 / Ss
        xs = x + ks * ys; ps00 = (1 - ks) * s00
        km0, km1 = m00 / Sm, m01 / Sm
        xm = x + v * dt + km0 * ym; vm = v + km1 * ym
        pm00 = (1 - km0) * m00; pm01 = (1 - km0) * m01; pm11 = m11 - km1 * m01
        xn = mu * xm + (1 - mu) * xs; vn = mu * vm
        dxs, dvs = xs - xn, 0 - vn
        dxm, dvm = xm - xn, vm - vn
        P00 = mu * (pm00 + dxm * dxm) + (1 - mu) * (ps00 + dxs * dxs)
        P01 = mu * (pm01 + dxm * dvm) + (1 - mu) * (dxs * dvs)
        P11 = mu * (pm11 + dvm * dvm) + (1 - mu) * (dvs * dvs)
        x, v = xn, vn
        out[i] = x; mus[i] = mu
    return out
