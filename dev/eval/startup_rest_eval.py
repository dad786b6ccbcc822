#!/usr/bin/env python3
"""What a new user's start-up rest gives (the heads that moved through their "rest"): every real clip filtered from its start with the defaults,
as `hkf-estimator --second-model none` then `hkf-filter --offline` give it to someone who has just started
hkf, whatever the head does in the first seconds; beside it the built-in wander alone (`rest_time=0`).

A real clip does not begin with a rest: on most of them the first seconds are a head that moves. What the
rest made of them is read from hkf-filter's own summary (measured or refused, the wander used). Per clip: still
jitter as a share of raw's, lag, and the lag over the best 1 euro setting's at that jitter (its 144 settings
swept on the clip itself: leave_one_out.py). The goals set for the refused rest: over the clips not used to tune the rest,
lag <= 0.30x the 1 euro's at equal jitter and still jitter <= 20 % of raw's; on every clip where the built-in
wander holds still jitter within 20 % of raw's, no more than half a frame (17 ms) of lag beyond it.

Tuning: the rest's rules (hkf_rest.h: the refusal at 0.6 deg^2 and 5 deg^2/s, the bound at 0.3 deg^2) were
chosen on the start-ups and longest still stretches of all these clips (docs/libhkf.md gives each one); with
any one clip left out, the gap between the still stretches and the moving start-ups still holds 0.6. The
stillness rule (HOLD's wander from the rest) was chosen on d14, d9, s20 and WolfgangLanger (rest_eval.py);
the summary row leaves those four out.

usage: startup_rest_eval.py [--build DIR] [--out DIR]
writes OUT/startup_rest/{startup_rest.md, startup_rest.png} and prints the table.
"""
import os
import re
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import evaluate  # noqa: E402
import leave_one_out  # noqa: E402

REST_TUNING = ["d14", "d9", "s20", "WolfgangLanger_Pexels"]  # the stillness rule's clips (rest_eval.py)
LAG_GOAL, SHARE_GOAL, BEYOND_BUILT_IN_MS = 0.30, 0.20, 17.0
SETTINGS = [("defaults (the start-up rest)", []), ("built-in wander (rest_time=0)", ["rest_time=0"])]


def rest_outcome(build, raw, work):
    """What the defaults' start-up rest became: hkf-filter's summary line about it."""
    result = subprocess.run([os.path.join(build, "tools", "hkf-filter"), "--offline", raw,
                             os.path.join(work, "summary.lcmlog")], capture_output=True, text=True)
    if result.returncode != 0:
        evaluate.fail(f"hkf-filter --offline {raw} exited {result.returncode}: {result.stderr.strip()}")
    said = [line for line in result.stderr.splitlines() if "the player's rest:" in line]
    if not said:
        return "?", 0, float("nan")
    measured = re.search(r"(\d+) measured, (\d+) spoiled \((\d+) of them refused.*the last rest measured: wander "
                         r"([\d.]+)", said[-1])
    if measured:
        return (f"measured ({measured.group(2)} spoiled, {measured.group(3)} of them refused)", int(measured.group(3)),
                float(measured.group(4)))
    none = re.search(r"none measured \((\d+) spoiled, (\d+) of them refused.*the built-in wander ([\d.]+)", said[-1])
    return (f"none taken ({none.group(1)} spoiled, {none.group(2)} of them refused)", int(none.group(2)),
            float(none.group(3))) if none else ("?", 0, float("nan"))


def measure_clip(build, out, types, work, path):
    name, raw, utime, clip = leave_one_out.real_clip(build, out, types, path)
    t, valid, z = clip["t"], clip["valid"], clip["z"]
    outcome, refused, wander = rest_outcome(build, raw, work)
    results = []
    for label, options in SETTINGS:
        m = evaluate.measure(t, valid, z, leave_one_out.hkf_output(build, raw, work, utime, options))
        share, ratio, euro_lag = leave_one_out.ratios(clip, m)
        results.append(dict(label=label, m=m, share=share, ratio=ratio, euro_lag=euro_lag))
    return dict(name=name, clip=clip, outcome=outcome, refused=refused, wander=wander, results=results)


def cell(r):
    if not np.isfinite(r["share"]):
        return "-"
    lag = f"{r['m']['lag_ms']:.0f} ms" if np.isfinite(r["m"]["lag_ms"]) else "no moving frames"
    ratio = f", {r['ratio']:.2f}x" if np.isfinite(r["ratio"]) and r["ratio"] > 0 else ""
    return f"{100 * r['share']:.0f} %, {lag}{ratio}"


def summary(rows, names, index):
    """Mean lag, mean 1 euro lag at each clip's jitter, their ratio and the mean share, over clips `names`."""
    picked = [row["results"][index] for row in rows if row["name"] in names]
    picked = [r for r in picked if np.isfinite(r["m"]["lag_ms"]) and r["euro_lag"] and np.isfinite(r["share"])]
    if not picked:
        return None
    lag = float(np.mean([r["m"]["lag_ms"] for r in picked]))
    euro = float(np.mean([r["euro_lag"] for r in picked]))
    return dict(clips=len(picked), lag=lag, ratio=lag / euro, share=float(np.mean([r["share"] for r in picked])))


def report(rows, out_dir):
    lines = ["# The start-up rest on real clips, as a new user gets it", "",
             "Made by `./run eval` (dev/eval/startup_rest_eval.py): each clip through `hkf-estimator --second-model "
             "none`, then `hkf-filter --offline` from its start. Cells: still jitter as a share of raw's, lag, lag "
             "over the best 1 euro setting's at that jitter.", "",
             "| clip | the start-up rest | wander used (deg²) | " + " | ".join(s[0] for s in SETTINGS) +
             " | lag beyond the built-in |", "| --- | --- | ---: |" + " --- |" * len(SETTINGS) + " ---: |"]
    for row in rows:
        own, built_in = row["results"]
        beyond = own["m"]["lag_ms"] - built_in["m"]["lag_ms"]
        tuned = " (rest tuning)" if row["name"] in REST_TUNING else ""
        beyond_text = f"{beyond:+.0f} ms" if np.isfinite(beyond) else "-"
        lines.append(f"| {row['name']}{tuned} | {row['outcome']} | {row['wander']:.3f} | {cell(own)} | "
                     f"{cell(built_in)} | {beyond_text} |")
    held_out = [row["name"] for row in rows if row["name"] not in REST_TUNING]
    lines += ["", "Means over the clips with moving frames (lag, the 1 euro's lag at each clip's jitter, their "
                  "ratio, still jitter):", ""]
    for label, names in (("not used to tune the rest", held_out), ("the rest's tuning clips", REST_TUNING)):
        for index, (setting, _) in enumerate(SETTINGS):
            s = summary(rows, names, index)
            if s:
                lines.append(f"- {label}, {setting}: {s['clips']} clips, lag {s['lag']:.1f} ms, {s['ratio']:.2f}x "
                             f"the 1 euro's, {100 * s['share']:.0f} % of raw's jitter")
    goals = summary(rows, held_out, 0)
    lines += ["", "Goals (the refused rest), the defaults on the clips not used to tune the rest:"]
    if goals:
        lines.append(f"- lag <= {LAG_GOAL:.2f}x the best 1 euro's: {goals['ratio']:.2f}x "
                     f"({'met' if goals['ratio'] <= LAG_GOAL else 'NOT met'})")
        lines.append(f"- still jitter <= {100 * SHARE_GOAL:.0f} % of raw's: {100 * goals['share']:.0f} % "
                     f"({'met' if goals['share'] <= SHARE_GOAL else 'NOT met'})")
    for row in rows:
        own, built_in = row["results"]
        if built_in["share"] <= SHARE_GOAL and np.isfinite(own["m"]["lag_ms"]) and np.isfinite(built_in["m"]["lag_ms"]):
            beyond = own["m"]["lag_ms"] - built_in["m"]["lag_ms"]
            lines.append(f"- {row['name']}: the built-in holds {100 * built_in['share']:.0f} % of raw's jitter; the "
                         f"defaults' lag {beyond:+.0f} ms beyond it "
                         f"({'met' if beyond <= BEYOND_BUILT_IN_MS else 'NOT met'}: at most {BEYOND_BUILT_IN_MS:.0f} ms)")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out_dir, "startup_rest.md"), "w") as f:
        f.write(text)
    print(text)


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    shown = [row for row in rows if all(np.isfinite(r["m"]["lag_ms"]) and np.isfinite(r["share"])
                                        for r in row["results"])]
    fig, ax = plt.subplots(figsize=(7.5, 4.6))
    for k, row in enumerate(shown):
        own, built_in = row["results"]
        color = f"C{k % 10}"
        ax.plot([100 * built_in["share"], 100 * own["share"]], [built_in["m"]["lag_ms"], own["m"]["lag_ms"]], "-",
                color=color, alpha=0.5)
        ax.plot([100 * built_in["share"]], [built_in["m"]["lag_ms"]], "^", color=color)
        ax.plot([100 * own["share"]], [own["m"]["lag_ms"]], "o", color=color, label=row["name"])
    ax.axvline(100 * SHARE_GOAL, color="0.8", ls=":")
    ax.set_xlabel("still jitter, % of raw's")
    ax.set_ylabel("lag, ms")
    ax.set_title("Each clip from its start: the defaults (o) against the built-in wander (^)", fontsize=10)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    build, out, types, out_dir, work = evaluate.script_folders(__doc__, "startup_rest")
    rows = []
    for path in evaluate.clips():
        started = time.time()
        rows.append(measure_clip(build, out, types, work, path))
        print(f"startup_rest_eval: {rows[-1]['name']}: {rows[-1]['outcome']} ({time.time() - started:.0f} s)",
              flush=True)
    report(rows, out_dir)
    plot(rows, os.path.join(out_dir, "startup_rest.png"))
    print(f"startup_rest_eval: {out_dir}/startup_rest.md, {out_dir}/startup_rest.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
