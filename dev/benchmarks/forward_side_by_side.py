#!/usr/bin/env python3
"""The second model's forward pass of two builds side by side, with onnxruntime held to the same level, at every
level and on 1 and 2 threads: in each of ROUNDS rounds, for each level and thread count, BEFORE's hkf-bench-layers,
NOW's, then onnxruntime_pass.py (through cpu_level_mask.c below this CPU's full level), one after another, so that a
neighbour's load falls on all three alike. A build without a level (BEFORE, older than the avx level) runs the best
it has below it, as it did on such a CPU; the cell says at which. Prints a markdown table: the median over the
rounds and, in brackets, the fastest round (the best estimate of the pass on an idle machine); ratios of the
fastest rounds. Figures as in
layer_levels.sh (WHENet 224x224, medians of 40 passes); the CPU must run AVX-512 for its row (else it is skipped).
usage: forward_side_by_side.py BEFORE_BENCH NOW_BENCH [ROUNDS]   (BENCH: a build's hkf-bench-layers, or
BENCH=GRAPH: with the rewritten graph that build reads, where dev/models/fast_layers.py changed between the two;
default .models/whenet_fast.onnx)"""
import os
import re
import statistics
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "dev", "eval"))
import evaluate  # noqa: E402  (cpu_info, cpu_named)
LEVELS = ("avx512", "avx2", "avx", "sse2")  # best first
MASK_LEVEL = {"avx512": "off", "avx2": "avx2", "avx": "avx", "sse2": "sse4_2"}  # onnxruntime's level for each of ours


def opencv_disable(level):
    with open(os.path.join(ROOT, "dev", "benchmarks", "opencv_cpu_levels.txt")) as f:
        for line in f:
            fields = line.split()
            if fields and not line.startswith("#") and fields[0] == level:
                return fields[1] if len(fields) > 1 else ""
    raise SystemExit(f"forward_side_by_side: no level {level} in opencv_cpu_levels.txt")


def ours(build, level, threads):
    """The pass of a build (BENCH or BENCH=GRAPH) on a CPU of `level`, and the level its layers ran at: a build
    without that level (an older one) runs the best it has below it, as it did on such a CPU."""
    bench, _, graph = build.partition("=")
    graph = graph or os.path.join(ROOT, ".models", "whenet_fast.onnx")
    for taken in LEVELS[LEVELS.index(level):]:
        env = dict(os.environ, HKF_SIMD=taken, OPENCV_CPU_DISABLE=opencv_disable(level))
        run = subprocess.run([bench, graph, "224", "224", "40", threads], capture_output=True, text=True, env=env)
        if run.returncode == 2 and "is not a level" in run.stderr:
            continue
        found = re.search(r"forward pass ([0-9.]+) ms", run.stdout)
        if run.returncode != 0 or not found:
            raise SystemExit(f"forward_side_by_side: {bench} failed at {taken} (exit {run.returncode}): {run.stderr.strip()}")
        return float(found.group(1)), taken
    raise SystemExit(f"forward_side_by_side: {bench} has no level at or below {level}")


def onnxruntime(level, threads, mask):
    env = dict(os.environ, HKF_PLAY_CPUID_LEVEL=MASK_LEVEL[level])
    if MASK_LEVEL[level] != "off":
        env["LD_PRELOAD"] = mask
    run = subprocess.run([os.path.join(ROOT, ".venv", "bin", "python"), os.path.join(ROOT, "dev", "benchmarks", "onnxruntime_pass.py"),
                          os.path.join(ROOT, ".models", "whenet.onnx"), threads, "40"], capture_output=True, text=True, env=env)
    if run.returncode != 0:
        raise SystemExit(f"forward_side_by_side: onnxruntime failed at {level}: {run.stderr.strip()}")
    return float(run.stdout.split()[0])


def cell(times):
    return f"{statistics.median(times):.2f} ({min(times):.2f})"


def main():
    if len(sys.argv) == 2 and sys.argv[1] in ("--help", "-h", "--version"):
        print(__doc__.strip())
        return 0
    if len(sys.argv) not in (3, 4):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    before, now = sys.argv[1], sys.argv[2]
    rounds = int(sys.argv[3]) if len(sys.argv) == 4 else 5
    now_bench = now.partition("=")[0]
    mask = os.path.join(os.path.dirname(os.path.abspath(now_bench)), "libhkf-cpu-level-mask.so")  # built beside it
    flags = evaluate.cpu_info()[1]
    levels = [level for level in LEVELS if level != "avx512" or "avx512f" in flags]
    if "cpuid_fault" not in flags or not os.path.exists(mask):
        raise SystemExit(f"forward_side_by_side: onnxruntime cannot be held to a level here (no cpuid_fault, or no {mask})")
    times, taken = {}, {}
    for r in range(rounds):
        for level in levels:
            for threads in ("1", "2"):
                for build, bench in (("before", before), ("now", now)):
                    ms, taken[(level, build)] = ours(bench, level, threads)
                    times.setdefault((level, threads, build), []).append(ms)
                times.setdefault((level, threads, "ort"), []).append(onnxruntime(level, threads, mask))
        print(f"round {r + 1} of {rounds} done", file=sys.stderr, flush=True)
    print(f"On {evaluate.cpu_named()}; {rounds} rounds.\n")
    print("| level | threads | before | now | onnxruntime, same level | now / before | now / onnxruntime |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for level in levels:
        for threads in ("1", "2"):
            b, n, o = (times[(level, threads, k)] for k in ("before", "now", "ort"))
            at = {k: "" if taken[(level, k)] == level else f" at {taken[(level, k)]}" for k in ("before", "now")}
            print(f"| {level} | {threads} | {cell(b)} ms{at['before']} | {cell(n)} ms{at['now']} | {cell(o)} ms | "
                  f"{min(n) / min(b):.2f}× | {min(n) / min(o):.2f}× |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
