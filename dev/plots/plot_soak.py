#!/usr/bin/env python3
"""Draws a soak run (hkf-soak's CSV): the node's memory and the latency
percentiles over time, with drops and non-finite poses marked, PNG.
usage: plot_soak.py SOAK.csv OUT.png"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv")
    parser.add_argument("out")
    args = parser.parse_args()
    try:
        with open(args.csv) as f:
            rows = list(csv.DictReader(f))
    except OSError as error:
        sys.exit(f"plot_soak: {error}")
    if not rows:
        sys.exit(f"plot_soak: {args.csv} has no rows")
    minutes = [float(r["elapsed_s"]) / 60 for r in rows]
    figure, (memory, latency) = plt.subplots(2, 1, sharex=True, figsize=(9, 6))
    memory.plot(minutes, [int(r["rss_kib"]) for r in rows], "k.-")
    memory.set_ylabel("hkf-filter RSS (KiB)")
    memory.set_ylim(bottom=0)
    dropped, non_finite = int(rows[-1]["dropped"]), int(rows[-1]["non_finite"])
    memory.set_title(f"soak: {int(rows[-1]['sent']):,} raw poses at 1 kHz, {dropped} dropped, "
                     f"{non_finite} non-finite")
    for key, style in (("p50_us", "b.-"), ("p99_us", "r.-"), ("max_us", "k:")):
        latency.plot(minutes, [float(r[key]) / 1000 for r in rows], style, label=key.replace("_us", ""))
    latency.set_yscale("log")
    latency.set_ylabel("raw -> filtered latency (ms)")
    latency.set_xlabel("minutes")
    latency.legend()
    figure.tight_layout()
    figure.savefig(args.out, dpi=100)
    print(f"plot_soak: wrote {args.out}")


if __name__ == "__main__":
    main()
