#!/usr/bin/env python3
"""libhkf's figures on each Cortex-M target, as a Markdown table: flash (the
whole library's text, and libhkf's share of the target test firmware as
linked: text + rodata of what init/update/predict and the default settings
need), RAM (sizeof hkf_filter_t, data, bss), the worst stack of each public
function (from GCC's -fcallgraph-info=su call graph), instructions per
hkf_update and the error against the x86 double build (from the qemu run of
the target test), and the runtime routines the library itself calls (its
undefined symbols: libm, soft-float, integer division, 64-bit multiply).
On the Cortex-M4F also cycles per update (cortex_m4_cycles.py: the executed
instructions priced by the Cortex-M4 manual), and a second table: libhkf
against the same filter written with CMSIS-DSP's matrix functions.
Reads the trees the hkf.mcu.* tests leave in BUILD/mcu/.
usage: mcu_figures.py BUILD_DIR"""
import glob
import os
import re
import subprocess
import sys

import cortex_m4_cycles

TARGETS = [("cortex-m0", "fixed"), ("cortex-m0", "float"), ("cortex-m4f", "fixed"), ("cortex-m4f", "float"),
           ("cortex-m7", "fixed"), ("cortex-m7", "float"), ("cortex-m7", "double")]
PUBLIC = ["hkf_init", "hkf_update", "hkf_update_pair", "hkf_predict", "hkf_extrapolate", "hkf_get_output", "hkf_reset",
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


def linked_share(map_file):
    """Bytes of text and rodata the firmware took from libhkf.a (from the linker map), less
    hkf_paper_settings: the target test runs both setting sets, a firmware needs one; and of them,
    those of the noise calibration (hkf_calibration.c), which a firmware may leave out."""
    text = open(map_file).read()
    text = text[text.index("Linker script and memory map"):]
    total = calibration = 0
    for section, address, size, origin in re.findall(r"^ (\.[\w.]+)\s*\n?\s+0x([0-9a-f]+)\s+0x([0-9a-f]+)\s+(\S+)",
                                                     text, re.M):
        if "libhkf.a" in origin and int(address, 16) != 0 and section.split(".")[1] in ("text", "rodata") \
                and section != ".rodata.hkf_paper_settings":
            total += int(size, 16)
            calibration += int(size, 16) if "hkf_calibration.c" in origin else 0
    return total, calibration


def runtime_routines(archive):
    """Runtime routines the library calls (its members' undefined symbols): soft-float (__aeabi_f*, __aeabi_d*),
    integer division, 64-bit multiply, and libm; and those only its optional settings table calls (it converts
    the ranges, doubles, for programs that read settings as text: firmware that does not call it does not link it)."""
    out = subprocess.run(["arm-none-eabi-nm", "-u", archive], capture_output=True, text=True, check=True).stdout
    names, table, member = set(), set(), ""
    for line in out.splitlines():
        if line.endswith(".obj:") or line.endswith(".o:"):
            member = line[:-1]
        elif line.strip().startswith("U "):
            (table if member.startswith("hkf_settings_table.c") else names).add(line.split()[-1])

    def routines(symbols):
        return sorted(n for n in symbols if re.match(r"__aeabi_(f|d|[ui]?[fd]2|l?div|uidiv|idiv|.*div|lmul)", n)
                      or re.match(r"__(add|sub|mul|div)[sd]f3", n))
    libm = sorted(n for n in names if n in {"exp", "expf", "sqrt", "sqrtf", "fabs", "fabsf", "__ieee754_exp",
                                             "__ieee754_expf", "__kernel_standard"})
    return routines(names), libm, sorted(set(routines(table)) - set(routines(names)))


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
        runs = {}
        for settings in ("paper", "defaults"):
            line = re.search(rf"^target \({settings}\): .*$", text_out, re.M)
            if line is None:
                sys.exit(f"mcu_figures: no '{settings}' result in {output}: rerun `ctest -R hkf.mcu`")
            errors = re.search(r"pitch (\d+) udeg, yaw (\d+) udeg, roll (\d+) udeg", line.group(0))
            runs[settings] = (int(re.search(r"(\d+) instructions each", line.group(0)).group(1)),
                              max(int(e) for e in errors.groups()) / 1000.0)
        state = re.search(r"sizeof\(hkf_filter_t\) (\d+) B", text_out)
        calibration = re.search(r"hkf_calibration_update: (\d+) instructions each; sizeof\(hkf_calibration_t\) (\d+) B",
                                text_out)
        if calibration is None:
            sys.exit(f"mcu_figures: no calibration result in {output}: rerun `ctest -R hkf.mcu`")
        lib = os.path.join(tree, "build", "libhkf", "libhkf.a")
        text, data, bss = size_of_archive(lib)
        own, calls = call_graph(os.path.join(tree, "build", "libhkf", "CMakeFiles", "hkf.dir", "src"))
        stacks = {f: worst_stack(f, own, calls) for f in PUBLIC}
        soft, libm, table_only = runtime_routines(lib)
        linked, calibration_linked = linked_share(os.path.join(tree, "build", "tests", "mcu", "hkf_target_test.map"))
        elf = os.path.join(tree, "build", "tests", "mcu", "hkf_target_test.elf")
        frames = len(re.findall(r"^\d", open(os.path.join(build, "mcu", "sequence.csv")).read(), re.M))
        cycles = [m4_cycles(elf, "hkf_update", "run_sequence", first, frames) for first in (0, frames)] \
            if cpu == "cortex-m4f" else None
        rows.append((cpu, real, text, linked, data, bss, int(state.group(1)), max(stacks.values()),
                     max(stacks, key=stacks.get), stacks["hkf_update"], runs, soft, libm, cycles,
                     (calibration_linked, int(calibration.group(1)), int(calibration.group(2))), table_only))
    print("| target | type | flash: library (linked) | data + bss | hkf_filter_t | worst stack (function) "
          "| stack of hkf_update | instructions per hkf_update: paper (defaults) | cycles (M4 estimate): paper "
          "(defaults) | largest error vs x86 double: paper (defaults) | runtime routines called |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |")
    for cpu, real, text, linked, data, bss, state, worst, worst_fn, update_stack, runs, soft, libm, cycles, _, _ in rows:
        routines = ", ".join(libm + soft) if (soft or libm) else "none"
        if len(soft) > 6:
            routines = ", ".join(libm) + (", " if libm else "") + f"{len(soft)} soft-float routines ({', '.join(soft[:4])}, …)"
        print(f"| {cpu} | {real} | {text:,} B ({linked:,} B) | {data + bss} B | {state} B | {worst} B (`{worst_fn}`) | {update_stack} B "
              f"| {runs['paper'][0]:,} ({runs['defaults'][0]:,}) | {f'{cycles[0]} ({cycles[1]})' if cycles else '–'} "
              f"| {runs['paper'][1]:.3f} ({runs['defaults'][1]:.3f}) mdeg | {routines} |")
    print("\n(Cortex-M0 built with -Os, the others with -O3. Flash: the whole libhkf.a, and in brackets what the "
          "target test firmware (hkf_init, hkf_update, hkf_predict, the default settings and the noise calibration; "
          "--gc-sections) took from "
          "it, less the second setting set the test also runs (hkf_paper_settings); error strings and unused "
          "presets are dropped there. Stack: own frame + deepest callee, from "
          "-fcallgraph-info=su; memcpy is the firmware's own and not counted. Instructions: qemu -icount, "
          "SysTick calibrated on a loop of known length; with the paper's settings (hkf_paper_settings) and, in brackets, "
          "the defaults (the motion adaptation; hkf_update alone, the calibration's step below). Cycles: Cortex-M4 only, the instructions hkf_update executes "
          "(qemu, one at a time) priced by the Cortex-M4 TRM, low..high for what the pipeline decides (branch "
          "refill 1-3, load/store pipelining). Error: the largest angle difference over the 448 frames of d10.mp4; "
          "fixed point against the double build fed the same Q16.16 input.)")
    print("\n| target | type | linked without the calibration | the calibration: linked | its state "
          "| instructions per hkf_calibration_update |")
    print("| --- | --- | ---: | ---: | ---: | ---: |")
    for row in rows:
        calibration_linked, calibration_insns, calibration_state = row[14]
        print(f"| {row[0]} | {row[1]} | {row[3] - calibration_linked:,} B | {calibration_linked:,} B "
              f"| {calibration_state} B | {calibration_insns:,} |")
    print("\n(The noise calibration (hkf/hkf_calibration.h) is its own part beside the filter: the defaults' run "
          "above has it; a firmware that leaves it out links the first column.)")
    table_routines = sorted({r for row in rows for r in row[15]})
    print("\nThe optional settings table (hkf/hkf_settings_table.h, not linked by the firmware) also calls: "
          + (", ".join(table_routines) if table_routines else "nothing more") + " (it converts its ranges, doubles).")
    cmsis_tree = os.path.join(build, "mcu", "cortex-m4f-cmsis_dsp")
    if not os.path.exists(os.path.join(cmsis_tree, "output.txt")):
        sys.exit(f"mcu_figures: no CMSIS-DSP comparison in {cmsis_tree}: run `ctest -R hkf.mcu.cortex-m4f.cmsis_dsp`")
    cmsis_out = open(os.path.join(cmsis_tree, "output.txt")).read()
    cmsis_errors = re.search(r"pitch (\d+) udeg, yaw (\d+) udeg, roll (\d+) udeg", cmsis_out)
    cmsis_insns = int(re.search(r"(\d+) instructions each", cmsis_out).group(1))
    cmsis_state = int(re.search(r"sizeof\(cmsis_filter_t\) (\d+) B", cmsis_out).group(1))
    cmsis_work = int(re.search(r"work matrices (\d+) B", cmsis_out).group(1))
    cmsis_cycles = m4_cycles(os.path.join(cmsis_tree, "build", "tests", "mcu", "hkf_cmsis_dsp_test.elf"),
                             "cmsis_filter_update", "main")
    hkf_row = next(r for r in rows if r[0] == "cortex-m4f" and r[1] == "float")
    hkf_insns, hkf_error, hkf_cycles = hkf_row[10]["paper"][0], hkf_row[10]["paper"][1], hkf_row[13][0]
    print("\n| Cortex-M4F, float, the paper's settings | instructions per update | cycles (M4 estimate) "
          "| largest error vs x86 double | filter state |")
    print("| --- | ---: | ---: | ---: | ---: |")
    print(f"| libhkf `hkf_update` | {hkf_insns:,} | {hkf_cycles} | {hkf_error:.3f} mdeg | {hkf_row[6]} B |")
    print(f"| the same filter with CMSIS-DSP 1.10.3 (`arm_mat_*_f32`, 6x6) | {cmsis_insns:,} | {cmsis_cycles} "
          f"| {max(int(e) for e in cmsis_errors.groups()) / 1000.0:.3f} mdeg | {cmsis_state} B + {cmsis_work:,} B of work matrices |")
    print(f"\n(The paper's settings, which both implement. CMSIS-DSP / libhkf: {cmsis_insns / hkf_insns:.1f}x the instructions. CMSIS-DSP from PyPI's cmsisdsp "
          "source distribution, -O3 with ARM_MATH_LOOPUNROLL; tests/mcu/cmsis_dsp_filter.c.)")


def m4_cycles(elf, function, caller, first=0, count=None):
    """'low..high' cycles per call of FUNCTION (from CALLER; calls first..first+count-1) on a Cortex-M4."""
    _, _, low, high, _ = cortex_m4_cycles.cycles_per_call(elf, "mps2-an386", function, caller, first, count)
    return f"{low:,.0f}..{high:,.0f}"


if __name__ == "__main__":
    main()
