#!/usr/bin/env python3
"""libhkf's figures on each Cortex-M target, as a Markdown table: flash (text),
RAM (sizeof hkf_filter_t, data, bss), the worst stack of each public function
(from GCC's -fcallgraph-info=su call graph), instructions per hkf_update and
the error against the x86 double build (from the qemu run of the target test),
and which runtime routines a firmware linking the test pulls in (libm,
soft-float). Reads the trees the hkf.mcu.* tests leave in BUILD/mcu/.
usage: mcu_figures.py BUILD_DIR"""
import glob
import os
import re
import subprocess
import sys

TARGETS = [("cortex-m0", "float"), ("cortex-m4f", "float"), ("cortex-m7", "float"), ("cortex-m7", "double")]
PUBLIC = ["hkf_init", "hkf_update", "hkf_predict", "hkf_extrapolate", "hkf_get_output", "hkf_reset",
          "hkf_set_center", "hkf_recenter", "hkf_get_center", "hkf_observation_noise"]


def call_graph(objects_dir):
    """Own stack (bytes) and callees per function, from the .ci files of one build."""
    own, calls = {}, {}
    for path in glob.glob(os.path.join(objects_dir, "*.ci")):
        for line in open(path):
            node = re.match(r'node: \{ title: "([^"]+)" label: "[^"]*\\n(\d+) bytes', line)
            if node:
                own[node.group(1)] = int(node.group(2))
            edge = re.match(r'edge: \{ sourcename: "([^"]+)" targetname: "([^"]+)"', line)
            if edge:
                calls.setdefault(edge.group(1), set()).add(edge.group(2))
    return own, calls


def worst_stack(name, own, calls, seen=()):
    """Own frame + the deepest callee's; library routines (memcpy) count 0."""
    if name in seen:
        raise ValueError(f"recursion through {name}")
    return own.get(name, 0) + max([worst_stack(c, own, calls, seen + (name,)) for c in calls.get(name, ())] or [0])


def size_of_archive(archive):
    out = subprocess.run(["arm-none-eabi-size", "-t", archive], capture_output=True, text=True, check=True).stdout
    text, data, bss = (int(v) for v in out.strip().split("\n")[-1].split()[:3])
    return text, data, bss


def runtime_routines(elf):
    """Runtime routines linked into the test program: soft-float (__aeabi_f*, __aeabi_d*) and libm."""
    out = subprocess.run(["arm-none-eabi-nm", elf], capture_output=True, text=True, check=True).stdout
    names = {line.split()[-1] for line in out.splitlines() if len(line.split()) >= 2}
    soft = sorted(n for n in names if re.match(r"__aeabi_(f|d|[ui]?[fd]2|l?div|uidiv|idiv|.*div)", n)
                  or re.match(r"__(add|sub|mul|div)[sd]f3", n))
    libm = sorted(n for n in names if n in {"exp", "expf", "sqrt", "sqrtf", "fabs", "fabsf", "__ieee754_exp",
                                             "__ieee754_expf", "__kernel_standard"})
    return soft, libm


def main():
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        sys.exit(0 if len(sys.argv) == 2 else 2)
    build = sys.argv[1]
    rows = []
    for cpu, real in TARGETS:
        tree = os.path.join(build, "mcu", f"{cpu}-{real}")
        output = os.path.join(tree, "output.txt")
        if not os.path.exists(output):
            sys.exit(f"mcu_figures: no {output}: run `ctest -R hkf.mcu` in {build} first")
        text_out = open(output).read()
        errors = re.search(r"pitch (\d+) udeg, yaw (\d+) udeg, roll (\d+) udeg", text_out)
        instructions = re.search(r"(\d+) instructions each", text_out)
        state = re.search(r"sizeof\(hkf_filter_t\) (\d+) B", text_out)
        lib = os.path.join(tree, "build", "libhkf", "libhkf.a")
        text, data, bss = size_of_archive(lib)
        own, calls = call_graph(os.path.join(tree, "build", "libhkf", "CMakeFiles", "hkf.dir", "src"))
        stacks = {f: worst_stack(f, own, calls) for f in PUBLIC}
        soft, libm = runtime_routines(os.path.join(tree, "build", "tests", "mcu", "hkf_target_test.elf"))
        rows.append((cpu, real, text, data, bss, int(state.group(1)), max(stacks.values()),
                     max(stacks, key=stacks.get), stacks["hkf_update"], int(instructions.group(1)),
                     max(int(e) for e in errors.groups()) / 1000.0, soft, libm))
    print("| target | type | flash (text) | data + bss | hkf_filter_t | worst stack (function) | stack of hkf_update "
          "| instructions per hkf_update | largest error vs x86 double | runtime routines pulled in |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |")
    for cpu, real, text, data, bss, state, worst, worst_fn, update_stack, insns, error, soft, libm in rows:
        routines = ", ".join(libm + soft) if (soft or libm) else "none"
        if len(soft) > 6:
            routines = ", ".join(libm) + (", " if libm else "") + f"{len(soft)} soft-float routines ({', '.join(soft[:4])}, …)"
        print(f"| {cpu} | {real} | {text:,} B | {data + bss} B | {state} B | {worst} B (`{worst_fn}`) | {update_stack} B "
              f"| {insns:,} | {error:.3f} mdeg | {routines} |")
    print("\n(stack: own frame + deepest callee, from -fcallgraph-info=su; memcpy, which hkf_init's struct copy "
          "calls, is the firmware's own and not counted. Instructions: qemu -icount, SysTick calibrated on a loop "
          "of known length; not cycles. Error: the largest angle difference over the 448 frames of d10.mp4.)")


if __name__ == "__main__":
    main()
