#!/usr/bin/env python3
"""A few hkf-filter settings on the truth clips, side by side (truth_eval.py's clips and metrics, without its
sweep): pooled over the held-out truth clips (made from clips that are not evaluate.TUNING_CLIPS) and over the
tuning ones, each setting's still jitter as a share of raw's, moving RMSE over raw's, onset delay over raw's
(ms) and overshoot (share of the move). The best 1 euro setting at each setting's jitter is given beside it.
The twin of real_clip_probe.py, for truth instead of real motion. Needs truth_eval.py's clips (made once).

usage: truth_probe.py [--build DIR] [--out DIR] SETTING...
SETTING: hkf-filter --set assignments joined by ';' ("" = the defaults), e.g. "stop_rate=0.25;start_rate=0.3".
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import evaluate  # noqa: E402
import truth_eval  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], epilog=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default=os.path.join(evaluate.ROOT, "build"))
    parser.add_argument("--out", default=os.path.join(evaluate.ROOT, "out", "eval"))
    parser.add_argument("settings", nargs="+")
    args = parser.parse_args()
    build, out = os.path.abspath(args.build), os.path.abspath(args.out)
    work = os.path.join(out, "truth", "probe")
    os.makedirs(work, exist_ok=True)
    specs = []
    for clip in [c for c in evaluate.clips() if "shared" in c]:
        specs += truth_eval.make_still_clips(build, out, clip, 2, 4)
    clips = [truth_eval.load(s, build) for s in specs]
    grid = [("raw", "-", lambda: truth_eval._Identity())]
    grid += [("hkf", s or "defaults", [o for o in s.split(";") if o]) for s in args.settings]
    grid += [g for g in evaluate.settings_grid() if g[0] == "1 euro"]
    rows = []
    for clip in clips:
        for setting in grid:
            roll = truth_eval.filter_output(build, clip, work, setting)
            rows.append({"clip": clip.name, "source": clip.source, "filter": setting[0], "setting": setting[1],
                         **truth_eval.clip_metrics(clip, roll)})
        truth_eval.log(f"{clip.name}: {len(grid)} settings")
    for label, keep in (("held out", lambda r: r["source"] not in evaluate.TUNING_CLIPS),
                        ("tuning clips", lambda r: r["source"] in evaluate.TUNING_CLIPS)):
        pooled = truth_eval.pool([r for r in rows if keep(r)])
        raw = next(p for p in pooled if p["filter"] == "raw")
        print(f"\n{label}: raw still jitter {raw['jitter']:.3f} deg, moving RMSE {raw['rmse_moving']:.2f} deg, "
              f"onset {raw['onset_ms']:.0f} ms\n")
        print("| setting | still jitter, share of raw | moving RMSE / raw's | onset - raw's | overshoot | "
              "best 1 euro at that jitter: RMSE / raw's |")
        print("| --- | ---: | ---: | ---: | ---: | ---: |")
        for p in [p for p in pooled if p["filter"] == "hkf"]:
            euro = truth_eval.at_equal_jitter(pooled, p["jitter"]).get("1 euro")
            euro_text = f"{euro['rmse_moving'] / raw['rmse_moving']:.2f}" if euro else "(none that still)"
            print(f"| {p['setting']} | {p['jitter'] / raw['jitter']:.0%} | {p['rmse_moving'] / raw['rmse_moving']:.2f} | "
                  f"{p['onset_ms'] - raw['onset_ms']:+.0f} ms | {p['overshoot_share']:.1%} | {euro_text} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
