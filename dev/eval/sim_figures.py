"""The paper's Figs. 6-8 redone on the simulated drive (sim_drive.py), each
with the number that states what it shows, in its title and printed:
- Fig. 6: raw vs constant R vs adaptive R (Eq. 8) in pitch and roll through
  a shoulder check (RMSE at |yaw| >= 60 deg);
- Fig. 7: loop closure (Eq. 9) in yaw near the centre (RMSE there);
- Fig. 8: both estimators through the same filter (RMSE over the drive)."""
import os

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import sim_drive  # noqa: E402

from sim_drive import DEFAULTS, PAPER, PAPER_ADAPTIVE_R, PAPER_CONSTANT_R  # noqa: E402


def window_around(t, centre_s, half_s):
    return (t >= centre_s - half_s) & (t <= centre_s + half_s)


def fig6(out, t, truth, glance, runs, estimator):
    z, valid, results = runs[estimator]
    turns = [i for i, g in enumerate(glance) if g.endswith("shoulder")]
    peak = max(turns, key=lambda i: abs(truth[i, 1]))
    w = window_around(t, t[peak], 2.5)
    names = [PAPER_CONSTANT_R, PAPER_ADAPTIVE_R]
    fig, axes = plt.subplots(3, 1, figsize=(10, 8), sharex=True)
    lines = []
    for row, (a, axis) in enumerate([(1, "yaw"), (0, "pitch"), (2, "roll")]):
        ax = axes[row]
        ax.plot(t[w], truth[w, a], "k-", lw=2, label="truth")
        ax.plot(t[w], results["raw"][w, a], ".", color="0.6", ms=4, label="raw (" + estimator + ")")
        for name, colour in zip(names, ("tab:blue", "tab:red")):
            ax.plot(t[w], results[name][w, a], "-", color=colour, lw=1.3, label=name)
        ax.set_ylabel(f"{axis} (deg)")
        if a != 1:
            rmse = {n: sim_drive.scores(results[n], truth, valid)["large"][a] for n in ["raw"] + names}
            text = ", ".join(f"{n} {v:.2f}" for n, v in rmse.items())
            ax.set_title(f"{axis} RMSE at |yaw| >= {sim_drive.LARGE_YAW:.0f} deg over the drive: {text}", fontsize=9)
            lines.append(f"Fig. 6 ({estimator}), {axis} RMSE at |yaw| >= {sim_drive.LARGE_YAW:.0f} deg: {text} deg")
    axes[0].legend(fontsize=8, loc="upper left")
    axes[-1].set_xlabel("time (s)")
    fig.suptitle(f"Fig. 6 on our data: a shoulder check ({glance[peak]}), {estimator}'s error model")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig6_adaptive_r.png"), dpi=110)
    plt.close(fig)
    return lines


def fig7(out, t, truth, glance, runs, estimator):
    z, valid, results = runs[estimator]
    calm = np.array([g == "" for g in glance]) & (np.linalg.norm(truth, axis=1) <= sim_drive.CENTRE_RADIUS)
    # the longest calm stretch
    best, start = (0, 0), None
    for i, c in enumerate(np.append(calm, False)):
        if c and start is None:
            start = i
        elif not c and start is not None:
            best = max(best, (i - start, start))
            start = None
    length, first = best
    w = np.zeros(len(t), dtype=bool)
    w[first:first + length] = True
    names = [PAPER_ADAPTIVE_R, PAPER]
    fig, ax = plt.subplots(figsize=(10, 4))
    ax.plot(t[w], truth[w, 1], "k-", lw=2, label="truth")
    ax.plot(t[w], results["raw"][w, 1], ".", color="0.6", ms=4, label="raw")
    for name, colour in zip(names, ("tab:blue", "tab:red")):
        ax.plot(t[w], results[name][w, 1], "-", color=colour, lw=1.3, label=name)
    rmse = {n: sim_drive.scores(results[n], truth, valid)["centre"][1] for n in ["raw"] + names}
    text = ", ".join(f"{n} {v:.2f}" for n, v in rmse.items())
    ax.set_title(f"yaw RMSE within {sim_drive.CENTRE_RADIUS:.0f} deg of the centre over the drive: {text}", fontsize=9)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("yaw (deg)")
    ax.legend(fontsize=8)
    fig.suptitle(f"Fig. 7 on our data: loop closure near the centre, {estimator}'s error model")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig7_loop_closure.png"), dpi=110)
    plt.close(fig)
    return [f"Fig. 7 ({estimator}), yaw RMSE within {sim_drive.CENTRE_RADIUS:.0f} deg of the centre: {text} deg"]


def fig8(out, t, truth, glance, runs):
    estimators = list(runs)
    turns = [i for i, g in enumerate(glance) if g.endswith("shoulder") or g.endswith("mirror")]
    w = window_around(t, t[turns[len(turns) // 2]], 6.0)
    fig, axes = plt.subplots(len(estimators), 1, figsize=(10, 3.2 * len(estimators)), sharex=True, squeeze=False)
    lines = []
    for row, estimator in enumerate(estimators):
        z, valid, results = runs[estimator]
        ax = axes[row, 0]
        ax.plot(t[w], truth[w, 1], "k-", lw=2, label="truth")
        ax.plot(t[w], results["raw"][w, 1], ".", color="0.6", ms=4, label=f"raw ({estimator})")
        ax.plot(t[w], results[DEFAULTS][w, 1], "-", color="tab:red", lw=1.3, label="hkf defaults")
        raw = sim_drive.scores(results["raw"], truth, valid)["all"]
        hkf = sim_drive.scores(results[DEFAULTS], truth, valid)["all"]
        text = (f"RMSE pitch/yaw/roll: raw {' / '.join(f'{v:.2f}' for v in raw)}, "
                f"hkf defaults {' / '.join(f'{v:.2f}' for v in hkf)}")
        ax.set_title(f"{estimator}: {text}", fontsize=9)
        ax.set_ylabel("yaw (deg)")
        ax.legend(fontsize=8, loc="upper left")
        lines.append(f"Fig. 8, {estimator}: {text} deg")
    axes[-1, 0].set_xlabel("time (s)")
    fig.suptitle("Fig. 8 on our data: both estimators through the same filter")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig8_estimators.png"), dpi=110)
    plt.close(fig)
    return lines


def draw(out, t, truth, glance, runs):
    first = next(iter(runs))
    lines = fig6(out, t, truth, glance, runs, first) + fig7(out, t, truth, glance, runs, first) + \
        fig8(out, t, truth, glance, runs)
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out, "sim_figures.md"), "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":  # the drive (sim_drive.py's tables, with its arguments), then its figures
    draw(*sim_drive.main())
